#pragma once
// /events/bond_breaks: the broken-bond log as extensible columns, one row per failed bond,
// buffered and written a block at a time like the series.
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "h5_io.hpp"
#include "shard/bonds.hpp"

namespace shard {

class BreakEventWriter {
 public:
  BreakEventWriter(hid_t file, std::size_t block_rows);

  void append(const std::vector<BondBreakEvent>& events);
  bool block_full() const { return time_.size() >= block_rows_; }
  void write();

 private:
  std::size_t block_rows_;
  h5::Column time_column_, step_column_, id_i_column_, id_j_column_, midpoint_column_;
  h5::Column sigma_vm_column_, sigma_axial_column_, tau_column_;
  h5::Column tension_column_, bending_column_, shear_column_, torsion_column_, mode_column_;
  std::vector<double> time_, sigma_vm_, sigma_axial_, tau_, tension_, bending_, shear_, torsion_;
  std::vector<std::int64_t> step_;
  std::vector<Index> id_i_, id_j_;
  std::vector<Vec3> midpoint_;
  std::vector<std::uint8_t> mode_;
};

}  // namespace shard
