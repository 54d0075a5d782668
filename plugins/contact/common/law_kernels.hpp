#pragma once
// A law's batch loops, one per instruction set (LANE_KERNELS in cmake/ShardPlugin.cmake: the law's
// kernel source compiled once per set, each object defining its <law>_kernel_<set>), and the choice
// among them, the same for every law.
#include <stdexcept>
#include <string>

#include "contact_lanes.hpp"
#include "lane_sets.hpp"

namespace shard::contact {

template <class Law>
struct LawKernels {
  using Make = LawKernel<Law> (*)(EffectSwitches);
  Make scalar;
  Make baseline;
  Make avx2;  // null where the build has no object for the set (off x86-64)
  Make avx512;

  // The loop in the lanes of `set`; a set without an object runs the baseline lanes.
  LawKernel<Law> operator()(LaneSet set, EffectSwitches on) const {
    switch (set) {
      case LaneSet::scalar: return scalar(on);
      case LaneSet::avx2: return (avx2 ? avx2 : baseline)(on);
      case LaneSet::avx512: return (avx512 ? avx512 : baseline)(on);
      case LaneSet::baseline: break;
    }
    return baseline(on);
  }

  // The loop in the lanes of `set`, which this machine must run (tests compare every set); `law`
  // names the law in the error.
  LawKernel<Law> required(LaneSet set, EffectSwitches on, const char* law) const {
    if (!lane_set_available(set))
      throw std::invalid_argument(std::string(law) + ": this machine cannot run the " +
                                  std::string(lane_set_name(set)) + " lanes");
    return (*this)(set, on);
  }
};

}  // namespace shard::contact
