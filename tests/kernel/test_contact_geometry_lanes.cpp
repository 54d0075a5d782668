// The contact pass's AVX-512 geometry and torques of touching particle pairs
// (kernel/src/contact_geometry_avx512.cpp) against the scalar rule they implement, slot by slot
// (kernel/src/contact_geometry_scalar.hpp, which the pass runs where no lanes do). Tolerance: none.
// The contact law reads these values, so the lanes must give the scalar rule's bits for every slot,
// whatever the sizes, masses, velocities and spins; a fused multiply-add, a reordered sum, a
// negation written as 0 - x or a lane out of order changes some of them. Wall slots are the
// caller's to write again: only the particle slots count.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "contact_geometry.hpp"
#include "contact_geometry_scalar.hpp"

using namespace shard;

namespace {

struct Block {
  std::vector<double> position, velocity, omega, radius, mass;  // particles
  std::vector<std::int32_t> i, j;                               // per slot
  std::vector<double> normal, velocity_rel, omega_rel, overlap, r_eff, m_eff;
  std::vector<double> force, couple, torque_a, torque_b;

  PairGeometryTile view() {
    return {position.data(), velocity.data(), omega.data(),     radius.data(),  mass.data(),  i.data(),
            j.data(),        normal.data(),   velocity_rel.data(), omega_rel.data(), overlap.data(), r_eff.data(),
            m_eff.data()};
  }
  PairLoadsTile loads() {
    return {radius.data(),  i.data(),     j.data(),           force.data(),   couple.data(),
            normal.data(), overlap.data(), torque_a.data(), torque_b.data()};
  }
};

// `particles` spheres of mixed sizes touching their neighbours in a random cloud, with random
// velocities and spins of mixed signs and scales; `slots` pairs of them, one in nine a wall.
Block make_block(std::size_t particles, std::size_t slots, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Block t;
  for (std::size_t k = 0; k < particles; ++k) {
    for (int d = 0; d < 3; ++d) {
      t.position.push_back(1e-3 * static_cast<double>(k % 10) + 2e-3 * unit(rng));
      t.velocity.push_back(std::ldexp(unit(rng), static_cast<int>(rng() % 20) - 10));
      t.omega.push_back(std::ldexp(unit(rng), static_cast<int>(rng() % 20) - 5));
    }
    t.radius.push_back(1e-3 * (1.5 + unit(rng)));
    t.mass.push_back(1e-5 * (2.0 + unit(rng)));
  }
  for (std::size_t c = 0; c < slots; ++c) {
    const auto a = static_cast<std::int32_t>(rng() % particles);
    auto b = static_cast<std::int32_t>(rng() % particles);
    if (b == a) b = (a + 1) % static_cast<std::int32_t>(particles);
    t.i.push_back(a);
    t.j.push_back(rng() % 9 == 0 ? -1 - static_cast<std::int32_t>(rng() % 3) : b);
  }
  for (auto* out : {&t.normal, &t.velocity_rel, &t.omega_rel, &t.torque_a, &t.torque_b}) out->assign(3 * slots, 0.0);
  // The contact law's outputs: forces and couples of mixed signs and scales, some zero.
  for (auto* out : {&t.force, &t.couple})
    for (std::size_t k = 0; k < 3 * slots; ++k)
      out->push_back(rng() % 7 == 0 ? 0.0 : std::ldexp(unit(rng), static_cast<int>(rng() % 30) - 15));
  for (auto* out : {&t.overlap, &t.r_eff, &t.m_eff}) out->assign(slots, 0.0);
  return t;
}

bool same_bits(const std::vector<double>& x, const std::vector<double>& y, std::size_t from, std::size_t count) {
  return std::memcmp(&x[from], &y[from], count * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("the AVX-512 pair geometry lanes give the scalar rule's bits slot by slot") {
  if (!pair_geometry_lanes_available()) {
    MESSAGE("this CPU has no AVX-512 F/BW/VL: the pair geometry lanes are not run here");
    return;
  }
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    constexpr std::size_t kSlots = 8 * 16;
    Block lanes = make_block(200, kSlots, seed);
    Block scalar = lanes;
    pair_geometry_avx512(lanes.view(), kSlots / 8);
    std::size_t walls = 0, overlapping = 0;
    for (std::size_t c = 0; c < kSlots; ++c) {
      if (lanes.j[c] < 0) {
        ++walls;
        continue;
      }
      particle_pair_geometry(scalar.view(), c);
      overlapping += scalar.overlap[c] > 0;
      CHECK(same_bits(lanes.normal, scalar.normal, 3 * c, 3));
      CHECK(same_bits(lanes.velocity_rel, scalar.velocity_rel, 3 * c, 3));
      CHECK(same_bits(lanes.omega_rel, scalar.omega_rel, 3 * c, 3));
      CHECK(same_bits(lanes.overlap, scalar.overlap, c, 1));
      CHECK(same_bits(lanes.r_eff, scalar.r_eff, c, 1));
      CHECK(same_bits(lanes.m_eff, scalar.m_eff, c, 1));
    }
    // Wall slots among the groups, and pairs both overlapping and apart.
    CHECK(walls > 4);
    CHECK(overlapping > 10);
    CHECK(overlapping < kSlots - walls);
  }
}

TEST_CASE("the AVX-512 pair torque lanes give the scalar rule's bits slot by slot") {
  if (!pair_geometry_lanes_available()) {
    MESSAGE("this CPU has no AVX-512 F/BW/VL: the pair torque lanes are not run here");
    return;
  }
  for (const std::uint64_t seed : {4u, 5u, 6u}) {
    constexpr std::size_t kSlots = 8 * 16;
    Block lanes = make_block(200, kSlots, seed);
    for (std::size_t c = 0; c < kSlots; ++c)
      if (lanes.j[c] >= 0) particle_pair_geometry(lanes.view(), c);  // a contact's geometry, as the pass has it
    Block scalar = lanes;
    pair_loads_avx512(lanes.loads(), kSlots / 8);
    std::size_t walls = 0;
    for (std::size_t c = 0; c < kSlots; ++c) {
      if (lanes.j[c] < 0) {
        ++walls;
        continue;
      }
      particle_pair_loads(scalar.loads(), c);
      CHECK(same_bits(lanes.torque_a, scalar.torque_a, 3 * c, 3));
      CHECK(same_bits(lanes.torque_b, scalar.torque_b, 3 * c, 3));
    }
    CHECK(walls > 4);
  }
}
