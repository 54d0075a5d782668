#pragma once
// The scalar rule of one listed pair in the contact pass's first loop (contact_candidates.hpp):
// the contact pass (simulation.cpp) runs it for the pairs no AVX-512 lanes take, and the lanes'
// test takes it as the reference. A particle pair is a candidate when not dist2 >= (r_a + r_b)^2
// and dist2 != 0, with dist2 = (dx dx + dy dy) + dz dz in Eigen's squaredNorm order (NaN counts as
// touching); a wall pair always is (the wall geometry makes its test). The pair geometry
// (contact_geometry_scalar.hpp) repeats this arithmetic, so both agree bit for bit, and the lanes
// (contact_candidates_avx512.cpp) repeat it operation for operation, which holds while no product
// is fused into a sum where this is compiled (the default instruction set has no FMA).
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "contact_candidates.hpp"

namespace shard {

// Pair q: its touching flag set to "is a candidate" and its history cleared when it stopped being
// one; its pair, ends and former flag written to slot c, which only a candidate keeps. Returns the
// next free slot. No branch on the test: whether a listed pair of a solid touches is close to
// random, and a branch on it is mispredicted.
[[gnu::always_inline]] inline std::size_t candidate_pair(const CandidateTile& t, std::size_t q, std::size_t c) {
  const std::int32_t a = t.first[q], j = t.second[q];
  const bool wall = j < 0;
  const std::int32_t b = wall ? a : j;
  const double* x = t.position;
  const double dx = x[3 * a] - x[3 * b], dy = x[3 * a + 1] - x[3 * b + 1], dz = x[3 * a + 2] - x[3 * b + 2];
  const double dist2 = (dx * dx + dy * dy) + dz * dz;
  const double reach = t.radius[a] + t.radius[b];
  const std::uint8_t now = static_cast<std::uint8_t>(wall | (!(dist2 >= reach * reach) & (dist2 != 0.0)));
  const std::uint8_t before = t.touching[q];
  if (before & ~now) std::fill_n(t.history + q * t.stride, t.stride, 0.0);
  t.touching[q] = now;
  t.touched[c] = before;
  t.pair[c] = q;
  t.i[c] = a;
  t.j[c] = j;
  return c + now;
}

}  // namespace shard
