#pragma once
// What the AVX-512 candidate test and the contact geometry share: the ends of 8 listed pairs and
// the difference of their positions, x_a - x_b per component, as the scalar loops take it.
// Included only where AVX-512 F/BW/VL are enabled.
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "shard/lanes/avx512_rows.hpp"

namespace shard::pair_rows {

struct Ends {
  __m256i a, j;  // the listed ends; j < 0 is a wall
  __m256i b;     // j, and a wall pair's own particle in its place (read twice)
  __mmask8 wall;
};

[[gnu::always_inline]] inline Ends ends(const std::int32_t* first, const std::int32_t* second, std::size_t k) {
  const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(first + k));
  const __m256i j = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(second + k));
  const __mmask8 wall = _mm256_cmplt_epi32_mask(j, _mm256_setzero_si256());
  return {a, j, _mm256_mask_blend_epi32(wall, j, a), wall};
}

// Row offsets (3 doubles a row) of the 8 indices, for the row loads.
[[gnu::always_inline]] inline void row_offsets(__m256i index, std::int64_t* out) {
  const __m512i k = _mm512_cvtepi32_epi64(index);
  _mm512_store_si512(out, _mm512_add_epi64(_mm512_slli_epi64(k, 1), k));
}

// d[c] = x_a - x_b of the rows at row_a and row_b.
[[gnu::always_inline]] inline void separation(const double* position, const std::int64_t* row_a,
                                              const std::int64_t* row_b, __m512d* d) {
  __m512d xa[3], xb[3];
  lanes::detail::load_rows4<3>(position, row_a, xa);
  lanes::detail::load_rows4<3>(position, row_b, xb);
  for (int c = 0; c < 3; ++c) d[c] = _mm512_sub_pd(xa[c], xb[c]);
}

}  // namespace shard::pair_rows
