#pragma once
// hertz_mindlin's batch loop per instruction set (hertz_kernel.cpp, compiled once per set) and
// the choice among them. Every set gives the same bits; scalar is the reference (T = double).
#include "../common/lane_sets.hpp"
#include "hertz_law.hpp"

namespace shard::hertz {

contact::LawKernel<HertzLaw> hertz_kernel_scalar(contact::EffectSwitches on);
contact::LawKernel<HertzLaw> hertz_kernel_baseline(contact::EffectSwitches on);
#if defined(__x86_64__)
contact::LawKernel<HertzLaw> hertz_kernel_avx2(contact::EffectSwitches on);
contact::LawKernel<HertzLaw> hertz_kernel_avx512(contact::EffectSwitches on);
#endif

inline contact::LawKernel<HertzLaw> hertz_kernel(contact::LaneSet set, contact::EffectSwitches on) {
  switch (set) {
#if defined(__x86_64__)
    case contact::LaneSet::avx512: return hertz_kernel_avx512(on);
    case contact::LaneSet::avx2: return hertz_kernel_avx2(on);
#endif
    case contact::LaneSet::scalar: return hertz_kernel_scalar(on);
    default: return hertz_kernel_baseline(on);
  }
}

}  // namespace shard::hertz
