#pragma once
// A law written once for any lane type T: T = double is one bond (the scalar reference, width 1),
// T = xsimd::batch<double, A> is one bond per SIMD lane (shard/lanes/xsimd_lanes.hpp). The law
// calls the operations below unqualified after `using namespace shard::lanes`: for double these
// overloads are found, for an xsimd batch argument-dependent lookup finds xsimd's of the same
// name. Each rounds as the IEEE operation it names, so a law without fused multiply-adds gives
// the same bits at every width (compile it with -ffp-contract=off: EXACT_LANES or LANE_KERNELS in
// cmake/ShardPlugin.cmake). The bond law (plugins/bond/beam_bond/beam_law.hpp) and the contact
// laws (plugins/contact/common/contact_lanes.hpp) are written in these operations.
//
// An object compiled for a wider instruction set (-mavx2, -mavx512f) instantiates a law for its
// batch type alone and calls none of the width-1 functions below: an inline function it emitted
// out of line could be the copy the linker keeps for every object of the module, and then run on
// a machine without that instruction set.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace shard::lanes {

// What a lane type brings besides arithmetic: its mask and index types, width, loads and stores.
template <class T>
struct Lanes;

template <>
struct Lanes<double> {
  using mask = bool;
  using index = std::int64_t;
  static constexpr std::size_t width = 1;
  [[gnu::always_inline]] static double gather(const double* base, index i) { return base[i]; }
  [[gnu::always_inline]] static void scatter(double* base, index i, double v) { base[i] = v; }
  [[gnu::always_inline]] static double load(const double* p) { return *p; }
  [[gnu::always_inline]] static void store(double* p, double v) { *p = v; }
  [[gnu::always_inline]] static index load_index(const std::int64_t* p) { return *p; }
  [[gnu::always_inline]] static double broadcast(double v) { return v; }
  [[gnu::always_inline]] static bool lane(bool m, std::size_t) { return m; }
  [[gnu::always_inline]] static std::uint64_t bits(bool m) { return m; }
};

inline double select(bool m, double a, double b) { return m ? a : b; }
inline bool any(bool m) { return m; }
inline double sqrt(double x) { return std::sqrt(x); }
inline double abs(double x) { return std::abs(x); }
inline double min(double a, double b) { return std::min(a, b); }
inline double max(double a, double b) { return std::max(a, b); }
inline double copysign(double a, double b) { return std::copysign(a, b); }
// -x, the sign flipped (+0 to -0 included); a law writes negate(x) rather than -x because the
// SIMD unary minus of xsimd 8.1 is not that operation (xsimd_lanes.hpp).
inline double negate(double x) { return -x; }

// A 3-vector stored x, y, z from p, as one lane each of x, y and z (xsimd_lanes.hpp: N vectors
// interleaved, transposed into three batches).
inline void load3(const double* p, double& x, double& y, double& z) { x = p[0], y = p[1], z = p[2]; }
inline void store3(double* p, double x, double y, double z) { p[0] = x, p[1] = y, p[2] = z; }

// std::max(0.0, x) as the scalar code writes it: x when 0 < x, else +0 (NaN and -0 included).
template <class T>
T clamp_at_zero(const T& x) {
  const T zero(0.0);
  return select(zero < x, x, zero);
}

// Eigen's order for a 3-vector dot product and squared norm: the first two terms as one packet.
// The contact laws keep it so that their results equal those of the Eigen code they replaced
// (same state hashes in docs/explanation/performance.md).
template <class T>
T dot3(const T& ax, const T& ay, const T& az, const T& bx, const T& by, const T& bz) {
  return (ax * bx + ay * by) + az * bz;
}

}  // namespace shard::lanes
