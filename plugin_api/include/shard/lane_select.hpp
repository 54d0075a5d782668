#pragma once
// c ? a : b through the bits, for the loops meant to run in SIMD lanes (the kernel's integration,
// the plugins' contact and bond lanes). With `?:` GCC sinks the computation of the side only one
// arm uses into a branch and, floating point being allowed to trap, cannot turn that branch back
// into a blend, so the loop would not vectorise; a bitwise select uses both sides unconditionally.
#include <bit>
#include <cstdint>

namespace shard {

inline double lane_select(bool c, double a, double b) {
  const std::uint64_t mask = -static_cast<std::uint64_t>(c);
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & mask) | (std::bit_cast<std::uint64_t>(b) & ~mask));
}

}  // namespace shard
