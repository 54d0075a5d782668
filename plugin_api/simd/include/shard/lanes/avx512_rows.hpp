#pragma once
// AVX-512 row loads: eight lanes' rows of contiguous doubles (a particle's Vec3 or Quat, a bond's
// state), each loaded whole and transposed in registers into one vector per component. On the
// AMD EPYC host this is three times faster than one gather instruction per component
// (docs/explanation/performance.md). Pure data movement: the values are the stored bits.
// Used by the SIMD lanes (xsimd_lanes.hpp) and the kernel's AVX-512 contact geometry.
#include <cstddef>
#include <cstdint>

#if defined(__AVX512F__)
#include <immintrin.h>

namespace shard::lanes {
namespace detail {

inline __m512i permute_index(const std::int64_t (&i)[8]) { return _mm512_loadu_si512(i); }

// Row l of C <= 4 doubles at base + offset[l] in both halves' lane order: a_k = rows k and k + 4.
// A masked load reads only the row's C doubles (the last particle's Vec3 ends its array).
template <std::size_t C>
[[gnu::always_inline]] inline __m512d rows_pair(const double* base, const std::int64_t* offset, int k) {
  constexpr __mmask8 m = static_cast<__mmask8>((1u << C) - 1);
  if constexpr (C == 4)
    return _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_loadu_pd(base + offset[k])),
                              _mm256_loadu_pd(base + offset[k + 4]), 1);
  else
    return _mm512_insertf64x4(_mm512_maskz_loadu_pd(m, base + offset[k]),
                              _mm512_castpd512_pd256(_mm512_maskz_loadu_pd(m, base + offset[k + 4])), 1);
}

// out[c] lane l = base[offset[l] + c], c < C <= 4: 8 row loads, a 4 x 8 transpose in registers.
template <std::size_t C>
[[gnu::always_inline]] inline void load_rows4(const double* base, const std::int64_t* offset, __m512d* out) {
  static constexpr std::int64_t lo[8] = {0, 1, 8, 9, 4, 5, 12, 13}, hi[8] = {2, 3, 10, 11, 6, 7, 14, 15};
  const __m512d a0 = rows_pair<C>(base, offset, 0), a1 = rows_pair<C>(base, offset, 1);
  const __m512d a2 = rows_pair<C>(base, offset, 2), a3 = rows_pair<C>(base, offset, 3);
  const __m512d t0 = _mm512_unpacklo_pd(a0, a1), t2 = _mm512_unpacklo_pd(a2, a3);
  out[0] = _mm512_permutex2var_pd(t0, permute_index(lo), t2);
  if constexpr (C > 2) out[2] = _mm512_permutex2var_pd(t0, permute_index(hi), t2);
  if constexpr (C > 1) {
    const __m512d t1 = _mm512_unpackhi_pd(a0, a1), t3 = _mm512_unpackhi_pd(a2, a3);
    out[1] = _mm512_permutex2var_pd(t1, permute_index(lo), t3);
    if constexpr (C > 3) out[3] = _mm512_permutex2var_pd(t1, permute_index(hi), t3);
  }
}

// The same for 4 < C <= 8: 8 row loads, an 8 x 8 transpose.
template <std::size_t C>
[[gnu::always_inline]] inline void load_rows8(const double* base, const std::int64_t* offset, __m512d* out) {
  static constexpr std::int64_t lo[8] = {0, 1, 8, 9, 4, 5, 12, 13}, hi[8] = {2, 3, 10, 11, 6, 7, 14, 15};
  static constexpr std::int64_t low_half[8] = {0, 1, 2, 3, 8, 9, 10, 11}, high_half[8] = {4, 5, 6, 7, 12, 13, 14, 15};
  constexpr __mmask8 m = static_cast<__mmask8>((1u << C) - 1);
  __m512d r[8];
  for (int l = 0; l < 8; ++l) r[l] = C == 8 ? _mm512_loadu_pd(base + offset[l]) : _mm512_maskz_loadu_pd(m, base + offset[l]);
  __m512d u[8];  // u[k]: rows 0-3 (k < 4) or 4-7 of components (k, k + 4) with k in order 0, 2, 1, 3
  for (int h = 0; h < 2; ++h) {
    const __m512d t0 = _mm512_unpacklo_pd(r[4 * h], r[4 * h + 1]), t1 = _mm512_unpackhi_pd(r[4 * h], r[4 * h + 1]);
    const __m512d t2 = _mm512_unpacklo_pd(r[4 * h + 2], r[4 * h + 3]), t3 = _mm512_unpackhi_pd(r[4 * h + 2], r[4 * h + 3]);
    u[4 * h + 0] = _mm512_permutex2var_pd(t0, permute_index(lo), t2);  // components 0, 4
    u[4 * h + 1] = _mm512_permutex2var_pd(t1, permute_index(lo), t3);  // 1, 5
    u[4 * h + 2] = _mm512_permutex2var_pd(t0, permute_index(hi), t2);  // 2, 6
    u[4 * h + 3] = _mm512_permutex2var_pd(t1, permute_index(hi), t3);  // 3, 7
  }
  for (std::size_t c = 0; c < C; ++c)
    out[c] = _mm512_permutex2var_pd(u[c % 4], permute_index(c < 4 ? low_half : high_half), u[4 + c % 4]);
}

}  // namespace detail

}  // namespace shard::lanes
#endif
