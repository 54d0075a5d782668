#pragma once
// The lane type a contact law is written for: double (one contact, the scalar reference) or an
// xsimd batch of doubles (as many contacts as the instruction set holds). The law uses only
// binary +, -, *, /, comparisons and these helpers (never unary minus: negate), each one IEEE
// operation per lane, so every width rounds exactly as the scalar code, provided no multiply-add
// is fused (the kernels are compiled with -ffp-contract=off: cmake/ShardPlugin.cmake, LANE_KERNELS).
//
// Every helper is a template on the lane type: a source compiled for AVX-512 then emits only
// symbols of its own batch type, and the linker cannot hand its code to a machine without it.
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include <xsimd/xsimd.hpp>

namespace shard::contact {

template <class T>
struct Lane;

// Its members are templates too, though they need not be: a full specialisation's functions are
// ordinary inline functions, which an object compiled for AVX-512 could emit for all to use.
template <>
struct Lane<double> {
  static constexpr std::size_t width = 1;
  template <class D = double>
  static D load(const D* p) { return *p; }
  template <class D = double>
  static void store(D* p, D v) { *p = v; }
};

template <class A>
struct Lane<xsimd::batch<double, A>> {
  using T = xsimd::batch<double, A>;
  static constexpr std::size_t width = T::size;
  static T load(const double* p) { return T::load_unaligned(p); }
  static void store(double* p, const T& v) { v.store_unaligned(p); }
};

// N contacts' 3-vectors, stored x, y, z interleaved from `p`, as three lanes of x, y and z. The
// transposition goes through a small aligned buffer, which GCC turns into loads and permutes; the
// gather and scatter instructions are slower here (AVX-512: 16.4 against 13.5 ns per contact-step
// with SSE2's two lanes, bench_contact).
template <std::same_as<double> T>
void load3(const double* p, T& x, T& y, T& z) {
  x = p[0], y = p[1], z = p[2];
}

template <class T>
  requires(!std::same_as<T, double>)
void load3(const double* p, T& x, T& y, T& z) {
  constexpr std::size_t N = T::size;
  alignas(64) double lanes[3][N];
  for (std::size_t l = 0; l < N; ++l)
    for (std::size_t c = 0; c < 3; ++c) lanes[c][l] = p[3 * l + c];
  x = T::load_aligned(lanes[0]), y = T::load_aligned(lanes[1]), z = T::load_aligned(lanes[2]);
}

template <std::same_as<double> T>
void store3(double* p, T x, T y, T z) {
  p[0] = x, p[1] = y, p[2] = z;
}

template <class T>
  requires(!std::same_as<T, double>)
void store3(double* p, const T& x, const T& y, const T& z) {
  constexpr std::size_t N = T::size;
  alignas(64) double lanes[3][N];
  x.store_aligned(lanes[0]), y.store_aligned(lanes[1]), z.store_aligned(lanes[2]);
  for (std::size_t l = 0; l < N; ++l)
    for (std::size_t c = 0; c < 3; ++c) p[3 * l + c] = lanes[c][l];
}

template <std::same_as<double> T>
T root(T x) { return std::sqrt(x); }

template <class A>
xsimd::batch<double, A> root(const xsimd::batch<double, A>& x) { return xsimd::sqrt(x); }

// c ? a : b per lane.
template <std::same_as<double> T>
T pick(bool c, T a, T b) { return c ? a : b; }

template <class A>
xsimd::batch<double, A> pick(const xsimd::batch_bool<double, A>& c, const xsimd::batch<double, A>& a,
                             const xsimd::batch<double, A>& b) {
  return xsimd::select(c, a, b);
}

// -x, the sign flipped, +0 to -0 included: xsimd 8.1's AVX-512 unary minus computes 0 - x, which
// turns +0 into +0 (and so a lane's bits from the scalar code's); a product with -1 is exact.
template <std::same_as<double> T>
T negate(T x) { return -x; }

template <class A>
xsimd::batch<double, A> negate(const xsimd::batch<double, A>& x) { return xsimd::batch<double, A>(-1.0) * x; }

// std::max(0.0, x) as the scalar code writes it: x when 0 < x, else +0 (NaN and -0 included).
template <class T>
T clamp_at_zero(const T& x) {
  const T zero(0.0);
  return pick(zero < x, x, zero);
}

// Eigen's order for a 3-vector dot product and squared norm: the first two terms as one packet.
// The laws keep it so that their results equal those of the Eigen code they replaced (same state
// hashes in docs/performance.md).
template <class T>
T dot3(const T& ax, const T& ay, const T& az, const T& bx, const T& by, const T& bz) {
  return (ax * bx + ay * by) + az * bz;
}

}  // namespace shard::contact
