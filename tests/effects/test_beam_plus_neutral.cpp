// At the neutral values of all four effects, beam_bond_plus must be beam_bond: both shipped
// plugin files are loaded through the PluginHost and driven on the same random bonds (stretched,
// sheared, bent, twisted, moving, some past their strength, some listed the other way round);
// every force, torque, energy, break flag and break stress must be bit-identical.
#include <doctest/doctest.h>

#include <cstring>
#include <map>
#include <random>

#include "bond_batch.hpp"
#include "shard/plugin_host.hpp"

namespace shard::effects_test {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) { return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z()); }

Quat random_rotation(std::mt19937_64& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1, 1);
  Vec3 axis(u(rng), u(rng), u(rng));
  axis.normalize();
  return Quat(Eigen::AngleAxisd(max_angle * u(rng), axis));
}

// Random bonded pairs, then a random deformation and motion of each.
BondScene random_pairs(std::size_t pairs, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> radius(0.3e-3, 0.5e-3);
  BondScene s;
  for (std::size_t k = 0; k < pairs; ++k) {
    const double r1 = radius(rng), r2 = radius(rng);
    const Vec3 x1(u(rng), u(rng), u(rng));
    Vec3 dir(u(rng), u(rng), u(rng));
    dir.normalize();
    const Index a = s.add_sphere(x1 * 1e-2, r1);
    const Index b = s.add_sphere(x1 * 1e-2 + (r1 + r2) * dir, r2);
    s.orientation[a] = random_rotation(rng, 3.0);
    s.orientation[b] = random_rotation(rng, 3.0);
    if (k % 3 == 0) s.add_bond(b, a);  // listed the other way round
    else s.add_bond(a, b);
  }
  return s;
}

void deform(BondScene& s, std::uint64_t seed, double scale) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::size_t p = 0; p < s.position.size(); ++p) {
    s.position[p] += scale * s.radius[p] * Vec3(u(rng), u(rng), u(rng));
    s.orientation[p] = (random_rotation(rng, 0.5 * scale) * s.orientation[p]).normalized();
    s.velocity[p] = 1e-2 * Vec3(u(rng), u(rng), u(rng));
    s.omega[p] = 10.0 * Vec3(u(rng), u(rng), u(rng));
  }
}

}  // namespace

TEST_CASE("beam_bond_plus at neutral values is bit-identical to beam_bond") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond_plus.so");
  // Damping on, so the rate paths are compared too.
  const std::map<std::string, ParamValue> common{{"damping", 1e-3}, {"rotational_damping", 1.0}};
  std::map<std::string, ParamValue> neutral = common;
  const PluginInfo& plus_info = host.find(PluginKind::Bond, "beam_bond_plus").info;
  int effects = 0;
  for (const std::string name : {"strength_weibull_modulus", "softening_ratio", "viscosity_time",
                                 "compression_stiffness_ratio"}) {
    bool found = false;
    for (const auto& spec : plus_info.params)
      if (spec.name == name) {
        REQUIRE(spec.neutral.has_value());
        neutral[name] = *spec.neutral;
        found = true;
        ++effects;
      }
    CHECK(found);
  }
  CHECK(effects == 4);

  const auto base = host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", common));
  const auto plus = host.make_bond("beam_bond_plus", host.params(PluginKind::Bond, "beam_bond_plus", neutral));

  BondScene a = random_pairs(2000, 7);
  BondScene b = a;
  a.initialize(*base);
  b.initialize(*plus);
  {
    BondBatch ba = a.batch(*base), bb = b.batch(*plus);
    const TimeStepLimit la = base->time_step_limit(ba), lb = plus->time_step_limit(bb);
    CHECK(same_bits(la.critical, lb.critical));
    CHECK(same_bits(la.recommended, lb.recommended));
  }
  std::size_t broken = 0, compared = 0;
  for (int step = 0; step < 4; ++step) {
    // Growing deformations: the last ones break a share of the bonds.
    deform(a, 100 + static_cast<std::uint64_t>(step), 0.01 * (step + 1));
    deform(b, 100 + static_cast<std::uint64_t>(step), 0.01 * (step + 1));
    a.compute(*base);
    b.compute(*plus);
    for (std::size_t k = 0; k < a.i.size(); ++k) {
      ++compared;
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
  }
  MESSAGE("compared ", compared, " bond evaluations, ", broken, " of them breaks");
  // The comparison covered both intact and breaking bonds.
  CHECK(broken > 100);
  CHECK(broken < compared / 2);
}

}  // namespace shard::effects_test
