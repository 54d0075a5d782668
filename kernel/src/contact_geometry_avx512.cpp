// The geometry of touching particle pairs 8 slots at a time in AVX-512 lanes (contact_geometry.hpp).
// Per slot the operations of particle_pair_geometry (contact_geometry_scalar.hpp), in its order:
// d = x_a - x_b, dist = sqrt((dx dx + dy dy) + dz dz), n = d / dist, overlap = (r_a + r_b) - dist,
// the arms s n with s_a = -(r_a - overlap / 2) and s_b = r_b - overlap / 2, the relative velocity
// (v_a + w_a x arm_a) - (v_b + w_b x arm_b) coefficient by coefficient, w_a - w_b,
// r_a r_b / (r_a + r_b) and m_a m_b / (m_a + m_b). Square roots and quotients are correctly rounded
// in lanes as in scalar code, and this file is compiled with -ffp-contract=off, so no product is
// fused into a sum: the same bits. The ends' rows are loaded whole and transposed
// (shard/lanes/avx512_rows.hpp), the outputs interleaved back in registers (xsimd_lanes.hpp).
#include "contact_geometry.hpp"

#include <cstdint>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#if defined(__x86_64__) && defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__)
#include "pair_rows_avx512.hpp"
#include "shard/lanes/avx512_rows.hpp"
#include "shard/lanes/xsimd_lanes.hpp"
#endif

namespace shard {

#if defined(__x86_64__) && defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__)

namespace {

using Batch = xsimd::batch<double, xsimd::avx512f>;

[[gnu::always_inline]] inline void store_rows(double* to, __m512d x, __m512d y, __m512d z) {
  lanes::store3(to, Batch(x), Batch(y), Batch(z));
}

// -x per lane: the sign bit flipped, as the scalar negation does (an xor of the integer bits: the
// floating-point xor needs AVX-512 DQ).
[[gnu::always_inline]] inline __m512d negate(__m512d x) {
  return _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(x), _mm512_set1_epi64(INT64_MIN)));
}

// a y - b z per lane: the cross product's coefficient as the scalar code writes it.
[[gnu::always_inline]] inline __m512d cross_term(__m512d a, __m512d y, __m512d b, __m512d z) {
  return _mm512_sub_pd(_mm512_mul_pd(a, y), _mm512_mul_pd(b, z));
}

void group_geometry(const PairGeometryTile& t, std::size_t s) {
  const pair_rows::Ends e = pair_rows::ends(t.i, t.j, s);
  const __m256i a = e.a, b = e.b;
  alignas(64) std::int64_t row_a[8], row_b[8];
  pair_rows::row_offsets(a, row_a);
  pair_rows::row_offsets(b, row_b);
  __m512d d[3];
  pair_rows::separation(t.position, row_a, row_b, d);
  const __m512d dx = d[0], dy = d[1], dz = d[2];
  const __m512d dist =
      _mm512_sqrt_pd(_mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz)));
  const __m512d ra = _mm512_i32gather_pd(a, t.radius, 8), rb = _mm512_i32gather_pd(b, t.radius, 8);
  const __m512d reach = _mm512_add_pd(ra, rb);
  const __m512d nx = _mm512_div_pd(dx, dist), ny = _mm512_div_pd(dy, dist), nz = _mm512_div_pd(dz, dist);
  const __m512d overlap = _mm512_sub_pd(reach, dist);
  const __m512d half_overlap = _mm512_mul_pd(_mm512_set1_pd(0.5), overlap);
  const __m512d sa = negate(_mm512_sub_pd(ra, half_overlap)), sb = _mm512_sub_pd(rb, half_overlap);
  const __m512d ax = _mm512_mul_pd(sa, nx), ay = _mm512_mul_pd(sa, ny), az = _mm512_mul_pd(sa, nz);
  const __m512d bx = _mm512_mul_pd(sb, nx), by = _mm512_mul_pd(sb, ny), bz = _mm512_mul_pd(sb, nz);
  __m512d va[3], vb[3], wa[3], wb[3];
  lanes::detail::load_rows4<3>(t.velocity, row_a, va);
  lanes::detail::load_rows4<3>(t.velocity, row_b, vb);
  lanes::detail::load_rows4<3>(t.omega, row_a, wa);
  lanes::detail::load_rows4<3>(t.omega, row_b, wb);
  const __m512d ubx = _mm512_add_pd(vb[0], cross_term(wb[1], bz, wb[2], by));
  const __m512d uby = _mm512_add_pd(vb[1], cross_term(wb[2], bx, wb[0], bz));
  const __m512d ubz = _mm512_add_pd(vb[2], cross_term(wb[0], by, wb[1], bx));
  const __m512d vx = _mm512_sub_pd(_mm512_add_pd(va[0], cross_term(wa[1], az, wa[2], ay)), ubx);
  const __m512d vy = _mm512_sub_pd(_mm512_add_pd(va[1], cross_term(wa[2], ax, wa[0], az)), uby);
  const __m512d vz = _mm512_sub_pd(_mm512_add_pd(va[2], cross_term(wa[0], ay, wa[1], ax)), ubz);
  store_rows(t.normal + 3 * s, nx, ny, nz);
  store_rows(t.velocity_rel + 3 * s, vx, vy, vz);
  store_rows(t.omega_rel + 3 * s, _mm512_sub_pd(wa[0], wb[0]), _mm512_sub_pd(wa[1], wb[1]), _mm512_sub_pd(wa[2], wb[2]));
  _mm512_storeu_pd(t.overlap + s, overlap);
  _mm512_storeu_pd(t.r_eff + s, _mm512_div_pd(_mm512_mul_pd(ra, rb), reach));
  const __m512d ma = _mm512_i32gather_pd(a, t.mass, 8), mb = _mm512_i32gather_pd(b, t.mass, 8);
  _mm512_storeu_pd(t.m_eff + s, _mm512_div_pd(_mm512_mul_pd(ma, mb), _mm512_add_pd(ma, mb)));
}

// The operations of particle_pair_loads (contact_geometry_scalar.hpp), in its order: arm x f
// coefficient by coefficient plus the couple on end a, arm_b x (-f) with f negated first minus the
// couple on b.
void group_loads(const PairLoadsTile& t, std::size_t s) {
  const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(t.i + s));
  const __m256i j = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(t.j + s));
  const __m256i b = _mm256_mask_blend_epi32(_mm256_cmplt_epi32_mask(j, _mm256_setzero_si256()), j, a);
  Batch f[3], n[3], c[3];
  lanes::load3(t.force + 3 * s, f[0], f[1], f[2]);
  lanes::load3(t.normal + 3 * s, n[0], n[1], n[2]);
  lanes::load3(t.couple + 3 * s, c[0], c[1], c[2]);
  const __m512d half_overlap = _mm512_mul_pd(_mm512_set1_pd(0.5), _mm512_loadu_pd(t.overlap + s));
  const __m512d sa = negate(_mm512_sub_pd(_mm512_i32gather_pd(a, t.radius, 8), half_overlap));
  const __m512d sb = _mm512_sub_pd(_mm512_i32gather_pd(b, t.radius, 8), half_overlap);
  const __m512d ax = _mm512_mul_pd(sa, n[0]), ay = _mm512_mul_pd(sa, n[1]), az = _mm512_mul_pd(sa, n[2]);
  const __m512d bx = _mm512_mul_pd(sb, n[0]), by = _mm512_mul_pd(sb, n[1]), bz = _mm512_mul_pd(sb, n[2]);
  const __m512d fx = f[0], fy = f[1], fz = f[2];
  store_rows(t.torque_a + 3 * s, _mm512_add_pd(cross_term(ay, fz, az, fy), c[0]),
             _mm512_add_pd(cross_term(az, fx, ax, fz), c[1]), _mm512_add_pd(cross_term(ax, fy, ay, fx), c[2]));
  const __m512d gx = negate(fx), gy = negate(fy), gz = negate(fz);
  store_rows(t.torque_b + 3 * s, _mm512_sub_pd(cross_term(by, gz, bz, gy), c[0]),
             _mm512_sub_pd(cross_term(bz, gx, bx, gz), c[1]), _mm512_sub_pd(cross_term(bx, gy, by, gx), c[2]));
}

}  // namespace

bool pair_geometry_lanes_available() {
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl");
}

void pair_geometry_avx512(const PairGeometryTile& t, std::size_t groups) {
  for (std::size_t g = 0; g < groups; ++g) group_geometry(t, 8 * g);
}

void pair_loads_avx512(const PairLoadsTile& t, std::size_t groups) {
  for (std::size_t g = 0; g < groups; ++g) group_loads(t, 8 * g);
}

#else

bool pair_geometry_lanes_available() { return false; }
void pair_geometry_avx512(const PairGeometryTile&, std::size_t) {}
void pair_loads_avx512(const PairLoadsTile&, std::size_t) {}

#endif

}  // namespace shard
