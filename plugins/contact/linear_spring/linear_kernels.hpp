#pragma once
// linear_spring's batch loop per instruction set (linear_kernel.cpp, compiled once per set) and
// the choice among them. Every set gives the same bits; scalar is the reference (T = double).
#include "../common/lane_sets.hpp"
#include "linear_law.hpp"

namespace shard::linear {

contact::LawKernel<LinearLaw> linear_kernel_scalar(contact::EffectSwitches on);
contact::LawKernel<LinearLaw> linear_kernel_baseline(contact::EffectSwitches on);
#if defined(__x86_64__)
contact::LawKernel<LinearLaw> linear_kernel_avx2(contact::EffectSwitches on);
contact::LawKernel<LinearLaw> linear_kernel_avx512(contact::EffectSwitches on);
#endif

inline contact::LawKernel<LinearLaw> linear_kernel(contact::LaneSet set, contact::EffectSwitches on) {
  switch (set) {
#if defined(__x86_64__)
    case contact::LaneSet::avx512: return linear_kernel_avx512(on);
    case contact::LaneSet::avx2: return linear_kernel_avx2(on);
#endif
    case contact::LaneSet::scalar: return linear_kernel_scalar(on);
    default: return linear_kernel_baseline(on);
  }
}

}  // namespace shard::linear
