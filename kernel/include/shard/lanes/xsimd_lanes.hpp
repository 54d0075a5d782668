#pragma once
// The SIMD lane type of shard/lanes/lanes.hpp: xsimd::batch<double, A>, one bond (or contact) per
// lane. A law is instantiated with batch<double, A> only in an object compiled for the
// architecture A (its intrinsics need the target's flags), and with that type alone
// (lanes.hpp). The overloads below are found by ordinary lookup, so a law calling them includes
// this header before its own definition; xsimd's sqrt, select, min, ... are found by
// argument-dependent lookup.
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <xsimd/xsimd.hpp>

#include "shard/lanes/lanes.hpp"

namespace shard::lanes {

template <class A>
struct Lanes<xsimd::batch<double, A>> {
  using type = xsimd::batch<double, A>;
  using mask = xsimd::batch_bool<double, A>;
  using index = xsimd::batch<std::int64_t, A>;
  static constexpr std::size_t width = type::size;
  // xsimd 8.1's batch::gather never reaches its AVX-512 or AVX2 kernels (it passes them one
  // template argument too many) and emulates them with a serial chain of 8 masked blends: the
  // gather instructions are called here directly.
  [[gnu::always_inline]] static type gather(const double* base, const index& i) {
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<A, xsimd::avx512f>) return _mm512_i64gather_pd(i, base, 8);
#endif
#if defined(__AVX2__)
    if constexpr (std::is_same_v<A, xsimd::avx2>) return _mm256_i64gather_pd(base, i, 8);
#endif
    return type::gather(base, i);
  }
  // Lanes with equal indices store the value of the last of them.
  [[gnu::always_inline]] static void scatter(double* base, const index& i, const type& v) {
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<A, xsimd::avx512f>) return _mm512_i64scatter_pd(base, i, v, 8);
#endif
    v.scatter(base, i);
  }
  [[gnu::always_inline]] static type load(const double* p) { return type::load_unaligned(p); }
  [[gnu::always_inline]] static void store(double* p, const type& v) { v.store_unaligned(p); }
  [[gnu::always_inline]] static index load_index(const std::int64_t* p) { return index::load_unaligned(p); }
  [[gnu::always_inline]] static type broadcast(double v) { return type(v); }
  [[gnu::always_inline]] static bool lane(const mask& m, std::size_t l) { return m.get(l); }
};

// -x: xsimd 8.1's AVX-512 unary minus computes 0 - x, which turns +0 into +0 (and so a lane's bits
// from the scalar code's); a product with -1 is exact and flips every sign.
template <class A>
xsimd::batch<double, A> negate(const xsimd::batch<double, A>& x) {
  return xsimd::batch<double, A>(-1.0) * x;
}

// N 3-vectors stored x, y, z interleaved from p, as three batches of x, y and z. The
// transposition goes through a small aligned buffer, which GCC turns into loads and permutes; the
// gather and scatter instructions are slower here (AVX-512: 16.4 against 13.5 ns per contact-step
// with SSE2's two lanes, bench_contact).
template <class A>
void load3(const double* p, xsimd::batch<double, A>& x, xsimd::batch<double, A>& y, xsimd::batch<double, A>& z) {
  using T = xsimd::batch<double, A>;
  constexpr std::size_t N = T::size;
  alignas(64) double lanes[3][N];
  for (std::size_t l = 0; l < N; ++l)
    for (std::size_t c = 0; c < 3; ++c) lanes[c][l] = p[3 * l + c];
  x = T::load_aligned(lanes[0]), y = T::load_aligned(lanes[1]), z = T::load_aligned(lanes[2]);
}

template <class A>
void store3(double* p, const xsimd::batch<double, A>& x, const xsimd::batch<double, A>& y,
            const xsimd::batch<double, A>& z) {
  constexpr std::size_t N = xsimd::batch<double, A>::size;
  alignas(64) double lanes[3][N];
  x.store_aligned(lanes[0]), y.store_aligned(lanes[1]), z.store_aligned(lanes[2]);
  for (std::size_t l = 0; l < N; ++l)
    for (std::size_t c = 0; c < 3; ++c) p[3 * l + c] = lanes[c][l];
}

}  // namespace shard::lanes
