#include "lane_sets.hpp"

#include <cstdlib>
#include <string>

namespace shard::contact {

bool lane_set_available(LaneSet set) {
  switch (set) {
    case LaneSet::scalar:
    case LaneSet::baseline:
      return true;
#if defined(__x86_64__)
    // GCC's check includes the operating system's support of the wide registers (XGETBV).
    case LaneSet::avx2:
      return __builtin_cpu_supports("avx2");
    case LaneSet::avx512:
      return __builtin_cpu_supports("avx512f");
#else
    case LaneSet::avx2:
    case LaneSet::avx512:
      return false;
#endif
  }
  return false;
}

std::string_view lane_set_name(LaneSet set) {
  switch (set) {
    case LaneSet::scalar: return "scalar";
    case LaneSet::baseline: return "baseline";
    case LaneSet::avx2: return "avx2";
    case LaneSet::avx512: return "avx512";
  }
  return "?";
}

LaneSet best_lane_set() {
  LaneSet best = LaneSet::baseline;
  for (LaneSet s : {LaneSet::avx2, LaneSet::avx512})
    if (lane_set_available(s)) best = s;
  if (const char* asked = std::getenv("SHARD_CONTACT_LANES"))
    for (LaneSet s : {LaneSet::scalar, LaneSet::baseline, LaneSet::avx2, LaneSet::avx512})
      if (lane_set_name(s) == asked && static_cast<int>(s) <= static_cast<int>(best)) best = s;
  return best;
}

}  // namespace shard::contact
