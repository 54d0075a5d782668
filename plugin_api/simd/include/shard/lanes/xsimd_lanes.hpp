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

#include "shard/lanes/avx512_rows.hpp"
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
  // out[c] lane l = base[offset[l] + c] for c < C: each lane's row of C contiguous doubles (a
  // particle's Vec3 or Quat, a bond's state). AVX-512 loads the rows and transposes them in
  // registers, three times faster than C gather instructions on the AMD EPYC host
  // (docs/explanation/performance.md); the narrower sets gather.
  template <std::size_t C>
  [[gnu::always_inline]] static void load_rows(const double* base, const std::int64_t* offset, type* out) {
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<A, xsimd::avx512f>) {
      __m512d v[C];
      if constexpr (C <= 4) {
        detail::load_rows4<C>(base, offset, v);
      } else {
        constexpr std::size_t head = C < 8 ? C : 8;
        detail::load_rows8<head>(base, offset, v);
        if constexpr (C > 8) {
          type rest[C - 8];
          load_rows<C - 8>(base + 8, offset, rest);
          for (std::size_t c = 8; c < C; ++c) v[c] = rest[c - 8];
        }
      }
      for (std::size_t c = 0; c < C; ++c) out[c] = v[c];
      return;
    }
#endif
    const index i = load_index(offset);
    for (std::size_t c = 0; c < C; ++c) out[c] = gather(base + c, i);
  }
  [[gnu::always_inline]] static type load(const double* p) { return type::load_unaligned(p); }
  [[gnu::always_inline]] static void store(double* p, const type& v) { v.store_unaligned(p); }
  [[gnu::always_inline]] static index load_index(const std::int64_t* p) { return index::load_unaligned(p); }
  [[gnu::always_inline]] static type broadcast(double v) { return type(v); }
  [[gnu::always_inline]] static bool lane(const mask& m, std::size_t l) { return m.get(l); }
  // Bit l set where lane l of m is: one instruction (xsimd 8.1's get(l) stores the whole mask as
  // bools for every lane it is asked about).
  [[gnu::always_inline]] static std::uint64_t bits(const mask& m) {
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<A, xsimd::avx512f>) return static_cast<__mmask8>(m);
#endif
#if defined(__AVX__)
    if constexpr (std::is_base_of_v<xsimd::avx, A>) return static_cast<std::uint64_t>(_mm256_movemask_pd(m));
#endif
#if defined(__SSE2__)
    if constexpr (std::is_base_of_v<xsimd::sse2, A>) return static_cast<std::uint64_t>(_mm_movemask_pd(m));
#endif
    std::uint64_t out = 0;
    for (std::size_t l = 0; l < width; ++l) out |= static_cast<std::uint64_t>(m.get(l)) << l;
    return out;
  }
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
#if defined(__AVX512F__)
// With AVX-512 the 8 vectors' 24 doubles are three loads or stores and each component two
// two-table permutes (vpermt2pd), no trip through memory: bench_kernel bonded, docs/explanation/performance.md.

inline void load3(const double* p, xsimd::batch<double, xsimd::avx512f>& x, xsimd::batch<double, xsimd::avx512f>& y,
                  xsimd::batch<double, xsimd::avx512f>& z) {
  // in0 = x0 y0 z0 x1 y1 z1 x2 y2, in1 = z2 x3 y3 z3 x4 y4 z4 x5, in2 = y5 z5 x6 y6 z6 x7 y7 z7
  static constexpr std::int64_t tx[8] = {0, 3, 6, 9, 12, 15, 0, 0}, ux[8] = {0, 1, 2, 3, 4, 5, 10, 13};
  static constexpr std::int64_t ty[8] = {1, 4, 7, 10, 13, 0, 0, 0}, uy[8] = {0, 1, 2, 3, 4, 8, 11, 14};
  static constexpr std::int64_t tz[8] = {2, 5, 8, 11, 14, 0, 0, 0}, uz[8] = {0, 1, 2, 3, 4, 9, 12, 15};
  const __m512d in0 = _mm512_loadu_pd(p), in1 = _mm512_loadu_pd(p + 8), in2 = _mm512_loadu_pd(p + 16);
  using detail::permute_index;
  x = _mm512_permutex2var_pd(_mm512_permutex2var_pd(in0, permute_index(tx), in1), permute_index(ux), in2);
  y = _mm512_permutex2var_pd(_mm512_permutex2var_pd(in0, permute_index(ty), in1), permute_index(uy), in2);
  z = _mm512_permutex2var_pd(_mm512_permutex2var_pd(in0, permute_index(tz), in1), permute_index(uz), in2);
}

inline void store3(double* p, const xsimd::batch<double, xsimd::avx512f>& x, const xsimd::batch<double, xsimd::avx512f>& y,
                   const xsimd::batch<double, xsimd::avx512f>& z) {
  // x and y into their places (z's left open), then z.
  static constexpr std::int64_t t0[8] = {0, 8, 0, 1, 9, 0, 2, 10}, u0[8] = {0, 1, 8, 3, 4, 9, 6, 7};
  static constexpr std::int64_t t1[8] = {0, 3, 11, 0, 4, 12, 0, 5}, u1[8] = {10, 1, 2, 11, 4, 5, 12, 7};
  static constexpr std::int64_t t2[8] = {13, 0, 6, 14, 0, 7, 15, 0}, u2[8] = {0, 13, 2, 3, 14, 5, 6, 15};
  using detail::permute_index;
  _mm512_storeu_pd(p, _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, permute_index(t0), y), permute_index(u0), z));
  _mm512_storeu_pd(p + 8, _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, permute_index(t1), y), permute_index(u1), z));
  _mm512_storeu_pd(p + 16, _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, permute_index(t2), y), permute_index(u2), z));
}
#endif

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
