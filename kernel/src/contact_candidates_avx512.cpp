// The candidate test of 8 listed pairs at a time in AVX-512 lanes (contact_candidates.hpp). Per
// pair the very operations of candidate_pair (contact_candidates_scalar.hpp): d = x_a - x_b per
// component, dist2 = (dx dx + dy dy) + dz dz, reach = r_a + r_b, candidate = wall or
// (not dist2 >= reach^2 and dist2 != 0), NaN counted as touching; this file is compiled with
// -ffp-contract=off, so no product is fused into a sum. The rows of the ends' positions are loaded
// whole and transposed (shard/lanes/avx512_rows.hpp), the radii gathered; the candidates are
// compacted with compress instructions, the touching bytes with BMI2's pdep/pext.
#include "contact_candidates.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>

#include "pair_rows_avx512.hpp"
#endif

namespace shard {

#if defined(__x86_64__) && defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__) && defined(__BMI2__)

bool candidate_lanes_available() {
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("bmi2");
}

std::size_t candidate_groups_avx512(const CandidateTile& t, std::size_t k, std::size_t groups, std::size_t c) {
  constexpr std::uint64_t kLowBits = 0x0101010101010101ull;
  const __m512i lane = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
  alignas(64) std::int64_t row_a[8], row_b[8];
  for (std::size_t g = 0; g < groups; ++g, k += 8) {
    const pair_rows::Ends e = pair_rows::ends(t.first, t.second, k);  // a wall pair tests its own particle
    const __m256i a = e.a, b = e.b, j = e.j;
    const __mmask8 wall = e.wall;
    pair_rows::row_offsets(a, row_a);
    pair_rows::row_offsets(b, row_b);
    __m512d d[3];
    pair_rows::separation(t.position, row_a, row_b, d);
    const __m512d dx = d[0], dy = d[1], dz = d[2];
    const __m512d dist2 =
        _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
    const __m512d reach = _mm512_add_pd(_mm512_i32gather_pd(a, t.radius, 8), _mm512_i32gather_pd(b, t.radius, 8));
    const __mmask8 within = _mm512_cmp_pd_mask(dist2, _mm512_mul_pd(reach, reach), _CMP_NGE_UQ) &
                            _mm512_cmp_pd_mask(dist2, _mm512_setzero_pd(), _CMP_NEQ_UQ);
    const __mmask8 now = wall | within;
    std::uint64_t before;
    std::memcpy(&before, t.touching + k, 8);
    const std::uint64_t now_bytes = _pdep_u64(now, kLowBits);
    for (std::uint64_t stopped = _pext_u64(before & ~now_bytes, kLowBits); stopped != 0; stopped &= stopped - 1) {
      const std::size_t q = k + static_cast<std::size_t>(std::countr_zero(stopped));
      std::fill_n(t.history + q * t.stride, t.stride, 0.0);
    }
    std::memcpy(t.touching + k, &now_bytes, 8);
    const std::uint64_t touched = _pext_u64(before, now_bytes * 0xFF);
    std::memcpy(t.touched + c, &touched, 8);
    const __m512i pair = _mm512_add_epi64(_mm512_set1_epi64(static_cast<long long>(k)), lane);
    _mm512_storeu_si512(t.pair + c, _mm512_maskz_compress_epi64(now, pair));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(t.i + c), _mm256_maskz_compress_epi32(now, a));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(t.j + c), _mm256_maskz_compress_epi32(now, j));
    c += static_cast<std::size_t>(std::popcount(static_cast<unsigned>(now)));
  }
  return c;
}

#else

bool candidate_lanes_available() { return false; }
std::size_t candidate_groups_avx512(const CandidateTile&, std::size_t, std::size_t, std::size_t c) { return c; }

#endif

}  // namespace shard
