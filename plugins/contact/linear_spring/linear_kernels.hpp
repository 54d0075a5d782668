#pragma once
// linear_spring's batch loop per instruction set (linear_kernel.cpp, compiled once per set) and
// the choice among them. Every set gives the same bits; scalar is the reference (T = double).
#include "../common/law_kernels.hpp"
#include "linear_law.hpp"

namespace shard::linear {

contact::LawKernel<LinearLaw> linear_kernel_scalar(contact::EffectSwitches on);
contact::LawKernel<LinearLaw> linear_kernel_baseline(contact::EffectSwitches on);
#if defined(__x86_64__)
contact::LawKernel<LinearLaw> linear_kernel_avx2(contact::EffectSwitches on);
contact::LawKernel<LinearLaw> linear_kernel_avx512(contact::EffectSwitches on);
inline constexpr contact::LawKernels<LinearLaw> linear_kernel{linear_kernel_scalar, linear_kernel_baseline, linear_kernel_avx2,
                                                          linear_kernel_avx512};
#else
inline constexpr contact::LawKernels<LinearLaw> linear_kernel{linear_kernel_scalar, linear_kernel_baseline, nullptr, nullptr};
#endif

}  // namespace shard::linear
