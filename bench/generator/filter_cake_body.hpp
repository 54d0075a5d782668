#pragma once
// The complex test body: the filter-cake shard (scenes/geometry/filter_cake_shard.stl,
// mm) filled at d = 1.42..1.92 mm, which holds ~4e4 spheres (41,132 at seed 1), the size of the
// seed's 41,788-sphere parent (1.5..2.0 mm gave 35,720). Shared by the benchmark and the picture.
#include <string>

#include "stl_fill.hpp"

namespace shard::bench {

inline constexpr double kShardDMin = 1.42e-3;  // m
inline constexpr double kShardDMax = 1.92e-3;  // m

inline stl_fill::StlFillSettings filter_cake_settings(double d_min = kShardDMin, double d_max = kShardDMax) {
  stl_fill::StlFillSettings s;
  s.file = "filter_cake_shard.stl";
  s.scale = 0.001;
  s.diameter_min = d_min;
  s.diameter_max = d_max;
  return s;
}

}  // namespace shard::bench
