// The contact pass's AVX-512 candidate lanes (kernel/src/contact_candidates_avx512.cpp) against the
// scalar rule they implement, pair by pair (kernel/src/contact_candidates_scalar.hpp, which the pass
// runs where no lanes do): a particle pair is a candidate when not (dist2 >= (r_a + r_b)^2) and
// dist2 != 0, dist2 = (dx dx + dy dy) + dz dz (NaN counts as touching), a wall pair always.
// Tolerance: none. The outputs are bytes and indices, and the lanes must make the same decision as
// the scalar rule for every pair, including pairs exactly at reach, one ulp either side, coincident
// centres and NaN positions; a changed comparison, a fused multiply-add or a lane out of order
// changes some of them.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "contact_candidates.hpp"
#include "contact_candidates_scalar.hpp"

using namespace shard;

namespace {

struct Tile {
  std::vector<double> position, radius, history;
  std::vector<std::int32_t> first, second;
  std::vector<std::uint8_t> touching;
  std::vector<std::size_t> pair;
  std::vector<std::int32_t> i, j;
  std::vector<std::uint8_t> touched;
  static constexpr std::size_t kStride = 3;

  CandidateTile view() {
    return {first.data(), second.data(), position.data(), radius.data(), touching.data(), history.data(),
            kStride,      pair.data(),   i.data(),        j.data(),      touched.data()};
  }
};

// The scalar rule over pairs [k, stop), as the contact pass runs it.
std::size_t reference(const CandidateTile& t, std::size_t k, std::size_t stop) {
  std::size_t c = 0;
  for (std::size_t q = k; q < stop; ++q) c = candidate_pair(t, q, c);
  return c;
}

// Pair m joins particles 2m and 2m + 1 (listed either way round) or particle 2m and a wall; the
// partner sits at a distance chosen among: exactly at reach (an axis offset of 1 with radii 0.5,
// so dist2 == reach^2 exactly), one ulp inside or outside, coincident, a NaN coordinate, random.
Tile make_tile(std::size_t pairs, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Tile t;
  t.position.resize(6 * pairs);
  t.radius.resize(2 * pairs);
  t.history.resize(Tile::kStride * pairs);
  for (std::size_t m = 0; m < pairs; ++m) {
    double* p = &t.position[6 * m];
    p[0] = 3.0 * static_cast<double>(m % 17), p[1] = 3.0 * static_cast<double>(m / 17), p[2] = 5.0;
    double offset[3] = {1.0, 0.0, 0.0};
    t.radius[2 * m] = 0.5, t.radius[2 * m + 1] = 0.5;
    switch (rng() % 7) {
      case 0: break;  // exactly at reach: not a candidate
      case 1: offset[0] = std::nextafter(1.0, 0.0); break;
      case 2: offset[0] = std::nextafter(1.0, 2.0); break;
      case 3: offset[0] = 0.0; break;  // coincident: not a candidate
      case 4: offset[1] = std::numeric_limits<double>::quiet_NaN(); break;
      default:
        for (double& o : offset) o = 1.2 * (unit(rng) - 0.5);
        t.radius[2 * m + 1] = 0.3 + 0.4 * unit(rng);
    }
    for (int d = 0; d < 3; ++d) p[3 + d] = p[d] + offset[d];
    const auto a = static_cast<std::int32_t>(2 * m);
    const std::uint64_t kind = rng() % 5;
    t.first.push_back(kind == 1 ? a + 1 : a);
    t.second.push_back(kind == 0 ? -1 - static_cast<std::int32_t>(rng() % 3) : kind == 1 ? a : a + 1);
    t.touching.push_back(static_cast<std::uint8_t>(rng() % 2));
    for (std::size_t s = 0; s < Tile::kStride; ++s) t.history[Tile::kStride * m + s] = t.touching.back() ? 1.0 + unit(rng) : 0.0;
  }
  t.pair.assign(pairs + 8, 0);
  t.i.assign(pairs + 8, 0);
  t.j.assign(pairs + 8, 0);
  t.touched.assign(pairs + 8, 0);
  return t;
}

}  // namespace

TEST_CASE("the AVX-512 candidate lanes decide, compact and clear exactly as the scalar rule") {
  if (!candidate_lanes_available()) {
    MESSAGE("this CPU has no AVX-512 F/BW/VL with BMI2: the candidate lanes are not run here");
    return;
  }
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    constexpr std::size_t kPairs = 8 * 125;
    Tile lanes = make_tile(kPairs, seed);
    Tile scalar = lanes;
    const std::vector<std::uint8_t> touching_before = lanes.touching;
    // Two calls, the second appending behind the first's candidates, as a tile's groups do.
    std::size_t c = candidate_groups_avx512(lanes.view(), 0, 60, 0);
    c = candidate_groups_avx512(lanes.view(), 480, 65, c);
    const std::size_t expected = reference(scalar.view(), 0, kPairs);
    REQUIRE(c == expected);
    std::size_t walls = 0, cleared = 0, exact = 0;
    for (std::size_t q = 0; q < kPairs; ++q) {
      CHECK(lanes.touching[q] == scalar.touching[q]);
      for (std::size_t s = 0; s < Tile::kStride; ++s)
        CHECK(std::memcmp(&lanes.history[3 * q + s], &scalar.history[3 * q + s], sizeof(double)) == 0);
      walls += lanes.second[q] < 0;
      cleared += touching_before[q] && !lanes.touching[q];
      exact += lanes.position[6 * q + 3] - lanes.position[6 * q] == 1.0 && lanes.position[6 * q + 4] == lanes.position[6 * q + 1];
    }
    for (std::size_t k = 0; k < c; ++k) {
      CHECK(lanes.pair[k] == scalar.pair[k]);
      CHECK(lanes.i[k] == scalar.i[k]);
      CHECK(lanes.j[k] == scalar.j[k]);
      CHECK(lanes.touched[k] == scalar.touched[k]);
    }
    // The tile holds every kind of pair: candidates and not, walls, cleared histories, exact reach.
    CHECK(c > kPairs / 4);
    CHECK(c < kPairs);
    CHECK(walls > 50);
    CHECK(cleared > 50);
    CHECK(exact > 50);
  }
}
