#pragma once
// Random bonded pairs for the bit-for-bit comparisons of two bond-step implementations
// (test_beam_block: blocked vs per-bond beam_bond, with and without effects; test_effects_neutral:
// beam_bond with its effect policies at neutral values vs plain beam_bond): stretched, sheared,
// bent, twisted, moving, some listed the other
// way round, and bit comparison helpers.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <utility>

#include "bond_pair.hpp"

namespace shard::test {

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
inline bool same_bits(const Vec3& a, const Vec3& b) {
  return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z());
}

inline Quat random_rotation(std::mt19937_64& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1, 1);
  Vec3 axis(u(rng), u(rng), u(rng));
  axis.normalize();
  return Quat(Eigen::AngleAxisd(max_angle * u(rng), axis));
}

struct RandomPairOptions {
  bool equal_radii_every_fifth = false;   // pairs of equal radii: the section's min() of a tie
  bool swap_ids_every_seventh = false;    // stable ids opposite to the storage order
};

// `pairs` touching pairs at random places and orientations; every third bond listed (j, i).
template <class Scene>
Scene random_pairs(std::size_t pairs, std::uint64_t seed, RandomPairOptions options = {}) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> radius(0.3e-3, 0.5e-3);
  Scene s;
  for (std::size_t k = 0; k < pairs; ++k) {
    const double r1 = radius(rng);
    const double r2 = options.equal_radii_every_fifth && k % 5 == 0 ? r1 : radius(rng);
    const Vec3 x1(u(rng), u(rng), u(rng));
    Vec3 dir(u(rng), u(rng), u(rng));
    dir.normalize();
    const Index a = s.add_sphere(x1 * 1e-2, r1);
    const Index b = s.add_sphere(x1 * 1e-2 + (r1 + r2) * dir, r2);
    s.orientation[a] = random_rotation(rng, 3.0);
    s.orientation[b] = random_rotation(rng, 3.0);
    if (k % 3 == 0) s.add_bond(b, a);
    else s.add_bond(a, b);
    if (options.swap_ids_every_seventh && k % 7 == 0)
      std::swap(s.id[static_cast<std::size_t>(a)], s.id[static_cast<std::size_t>(b)]);
  }
  return s;
}

// Positions moved by up to `scale` radii, rotations by up to rotation_factor x scale rad, and a
// random velocity (1e-2 m/s) and spin (10 rad/s) for every particle.
template <class Scene>
void deform(Scene& s, std::uint64_t seed, double scale, double rotation_factor) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::size_t p = 0; p < s.position.size(); ++p) {
    s.position[p] += scale * s.radius[p] * Vec3(u(rng), u(rng), u(rng));
    s.orientation[p] = (random_rotation(rng, rotation_factor * scale) * s.orientation[p]).normalized();
    s.velocity[p] = 1e-2 * Vec3(u(rng), u(rng), u(rng));
    s.omega[p] = 10.0 * Vec3(u(rng), u(rng), u(rng));
  }
}

// Checks that two evaluations of the same bonds wrote the same bits (force, torques, energy,
// break flag, stress at failure); returns how many bonds broke.
template <class Scene>
std::size_t check_same_outputs(const Scene& a, const Scene& b) {
  std::size_t broken = 0;
  for (std::size_t k = 0; k < a.i.size(); ++k) {
    REQUIRE(a.broken[k] == b.broken[k]);
    broken += a.broken[k];
    CHECK(same_bits(a.force[k], b.force[k]));
    CHECK(same_bits(a.torque_i[k], b.torque_i[k]));
    CHECK(same_bits(a.torque_j[k], b.torque_j[k]));
    CHECK(same_bits(a.energy[k], b.energy[k]));
    if (a.broken[k]) {
      CHECK(same_bits(a.stress[k].sigma_vm, b.stress[k].sigma_vm));
      CHECK(a.stress[k].dominant == b.stress[k].dominant);
    }
  }
  return broken;
}

}  // namespace shard::test
