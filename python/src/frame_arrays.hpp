#pragma once
// The arrays of one frame as the analysis library takes them (ParticleSample, BondList), built from
// the numpy arrays a caller hands in and checked once; and a size distribution as a dict.
#include <pybind11/pybind11.h>

#include <vector>

#include "arrays.hpp"
#include "shard/analysis/body_statistics.hpp"
#include "shard/analysis/components.hpp"
#include "shard/analysis/fragment_table.hpp"
#include "shard/analysis/size_distribution.hpp"

namespace shard::python {

// A frame's particle arrays and surviving bonds, owned here so the library's spans point into them.
struct FrameArrays {
  std::vector<Index> id;
  std::vector<Vec3> position, velocity;
  std::vector<double> radius, mass;
  std::vector<std::int32_t> body;
  std::vector<Index> bond_i, bond_j;

  analysis::ParticleSample sample() const { return {id, position, velocity, radius, mass, body}; }
  analysis::BondList bonds() const { return {bond_i, bond_j}; }
};

// Throws ValueError when the arrays differ in length or a bond names a row outside the frame.
FrameArrays frame_arrays(const In<Index>& id, const In<double>& position, const In<double>& velocity,
                         const In<double>& radius, const In<double>& mass, const In<std::int32_t>& body,
                         const In<Index>& bonds);

// points (as arrays d, cumulative), fragments, total_mass, x10, x50, x90, fines_size, fines_mass.
py::dict distribution_dict(const analysis::SizeDistribution& fsd);

// The per-body table as stored (columns, figures), each body's distribution and the pooled one.
py::dict body_report_dict(const analysis::BodyReport& report);

}  // namespace shard::python
