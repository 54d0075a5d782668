#pragma once
// The quasi-static figure of a loading run, one rule for `shard run`'s log and `shard bending`'s
// report: the largest kinetic / stored elastic energy over the rows before the first broken bond
// whose load is at least a fifth of the peak. Below that the pins are still seating and the
// elastic energy is near zero, so the ratio says nothing about inertia in the test.
// `shard run` (and every measurement command's run) passes the deformation's kinetic energy, less
// the rigid-body motion (deformation_kinetic.hpp); `shard bending` reads the run file's total
// kinetic energy series, an upper bound of it (equal when the beam neither slides nor sinks).
#include <algorithm>
#include <cstddef>
#include <span>

namespace shard::analysis {

inline constexpr double kQuasiStaticLoadFraction = 0.2;

// Rows k < min(kinetic.size(), elastic.size(), load.size()): the caller passes the rows before
// the first break (and before the peak, if it wants).
inline double max_kinetic_to_elastic(std::span<const double> load, std::span<const double> kinetic,
                                     std::span<const double> elastic, double peak_load) {
  double ratio = 0;
  if (!(peak_load > 0)) return ratio;
  const std::size_t rows = std::min({load.size(), kinetic.size(), elastic.size()});
  for (std::size_t k = 0; k < rows; ++k)
    if (load[k] >= kQuasiStaticLoadFraction * peak_load && elastic[k] > 0) ratio = std::max(ratio, kinetic[k] / elastic[k]);
  return ratio;
}

}  // namespace shard::analysis
