#pragma once
// hertz_mindlin's batch loop per instruction set (hertz_kernel.cpp, compiled once per set) and
// the choice among them. Every set gives the same bits; scalar is the reference (T = double).
#include "../common/law_kernels.hpp"
#include "hertz_law.hpp"

namespace shard::hertz {

contact::LawKernel<HertzLaw> hertz_kernel_scalar(contact::EffectSwitches on);
contact::LawKernel<HertzLaw> hertz_kernel_baseline(contact::EffectSwitches on);
#if defined(__x86_64__)
contact::LawKernel<HertzLaw> hertz_kernel_avx2(contact::EffectSwitches on);
contact::LawKernel<HertzLaw> hertz_kernel_avx512(contact::EffectSwitches on);
inline constexpr contact::LawKernels<HertzLaw> hertz_kernel{hertz_kernel_scalar, hertz_kernel_baseline, hertz_kernel_avx2,
                                                          hertz_kernel_avx512};
#else
inline constexpr contact::LawKernels<HertzLaw> hertz_kernel{hertz_kernel_scalar, hertz_kernel_baseline, nullptr, nullptr};
#endif

}  // namespace shard::hertz
