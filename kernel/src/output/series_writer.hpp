#pragma once
// /series: one extensible column per quantity; per wall three [n,3] columns and two [n] ones. Rows are
// buffered in memory and written a block at a time, so append() is a few stores into vectors
// reserved up front (no allocation per row).
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "h5_io.hpp"
#include "shard/output.hpp"

namespace shard {

class SeriesWriter {
 public:
  SeriesWriter(hid_t file, const std::vector<std::string>& wall_names, std::size_t block_rows);

  void append(const SeriesRow& row);
  bool block_full() const { return step_.size() >= block_rows_; }
  // Writes the buffered rows to the file and empties the buffer (capacity kept).
  void write();

 private:
  struct WallColumns {
    h5::Column force, torque, displacement, impact_energy, impacts;
    std::vector<Vec3> force_rows, torque_rows, displacement_rows;
    std::vector<double> impact_energy_rows;
    std::vector<std::int64_t> impacts_rows;
  };

  std::size_t block_rows_;
  h5::Column step_column_, time_column_, kinetic_column_, bond_column_, contact_column_;
  h5::Column intact_column_, broken_column_, contacts_column_;
  std::vector<std::int64_t> step_, intact_, broken_, contacts_;
  std::vector<double> time_, kinetic_, bond_, contact_;
  std::vector<WallColumns> walls_;
};

}  // namespace shard
