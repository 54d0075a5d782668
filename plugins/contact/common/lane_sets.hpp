#pragma once
// The instruction sets a law's lane kernel is compiled for (cmake/ShardPlugin.cmake,
// LANE_KERNELS: one object per set, with SHARD_LANES_<SET> defined) and the choice among them
// at run time. Every set gives the same bits (lanes.hpp), so the choice changes speed only.
#include <string_view>

namespace shard::contact {

enum class LaneSet { scalar, baseline, avx2, avx512 };

// The widest set this machine runs; SHARD_CONTACT_LANES=scalar|baseline|avx2|avx512 asks for a
// narrower one (a wider one than the machine has is ignored).
LaneSet best_lane_set();
// Whether this build holds `set` and this machine can run it (tests compare every available set).
bool lane_set_available(LaneSet set);
std::string_view lane_set_name(LaneSet set);

}  // namespace shard::contact
