// Breakage and order independence through the product path: the plugin .so loaded by the
// PluginHost, bonds run and broken by the kernel's Simulation, events recorded by the kernel.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "beam_pair_sim.hpp"
#include "beam_plugin.hpp"

using namespace shard;
using namespace shard::test;

TEST_CASE("slow tension of a three-sphere chain breaks where E_b strain = sigma_crit (within 0.5 %)") {
  const BeamPlugin beam({{"rotational_damping", 0.0}});  // Table I E_b and sigma_crit, breakage on
  const beam::BeamBondParams p;
  const BeamNumbers b = numbers_of(p);

  // A (fixed) - B (free) - C (fixed, pulled along the axis at constant speed): both bonds carry
  // half the opening, B follows quasi-statically (its period is ~1e-4 of the loading time).
  SimulationSetup setup;
  const Vec3 start(0.002, 0.001, -0.003);
  for (int k = 0; k < 3; ++k) setup.particles.add(start + k * b.l0 * kPairAxis, kRadius, kDensity);
  setup.particles.flags[0] = setup.particles.flags[2] = kFixed;
  setup.bonds = {{0, 1}, {1, 2}};
  setup.bond = &beam.model();
  Simulation sim(std::move(setup));

  const double speed = 1e-3;  // m/s
  sim.particles().velocity[2] = speed * kPairAxis;
  const double strain_crit = p.critical_stress / p.youngs_modulus;
  const auto budget = static_cast<std::int64_t>(2 * 2 * b.l0 * strain_crit / speed / sim.dt());
  while (sim.bonds_broken() == 0 && sim.step_count() < budget) {
    sim.particles().position[2] += speed * sim.dt() * kPairAxis;
    sim.step();
  }
  REQUIRE(sim.break_events().size() >= 1);
  const BondBreakEvent& e = sim.break_events().front();
  const double opening = (sim.particles().position[2] - sim.particles().position[0]).norm() - 2 * b.l0;
  const double strain_at_break = opening / (2 * b.l0);
  std::printf("three-sphere tension: E_b strain at break %.6g Pa (sigma_crit %.6g, %+.3f %%), recorded %.6g Pa\n",
              p.youngs_modulus * strain_at_break, p.critical_stress,
              100 * (p.youngs_modulus * strain_at_break / p.critical_stress - 1), e.stress.sigma_vm);
  CHECK(p.youngs_modulus * strain_at_break == doctest::Approx(p.critical_stress).epsilon(0.005));
  CHECK(e.stress.sigma_vm >= p.critical_stress);
  CHECK(e.stress.sigma_vm == doctest::Approx(p.critical_stress).epsilon(0.005));
  CHECK(e.stress.dominant == BondFailureMode::Tension);
  CHECK(e.stress.tension == doctest::Approx(e.stress.sigma_vm).epsilon(1e-3));
  CHECK(sim.bonds().size() == 1);
}

TEST_CASE("a pair thrown together is compressed by half its length without breaking, then fails in tension") {
  const BeamPlugin beam({{"rotational_damping", 0.0}});
  const beam::BeamBondParams p;
  const BeamNumbers b = numbers_of(p);
  SimulationSetup setup = pair_setup(beam.model());
  const double m = setup.particles.mass[0], I = setup.particles.inertia[0];
  const ModeTheory axial = theory_of(Mode::Axial, b, m, I);
  // Relative speed for an axial strain amplitude of 0.5: the spheres pass deep into each other
  // (no contact model here), the bond alone resists.
  const double approach = 0.5 * b.l0 * axial.omega();
  setup.particles.velocity[0] = 0.5 * approach * kPairAxis;
  setup.particles.velocity[1] = -0.5 * approach * kPairAxis;
  Simulation sim(std::move(setup));

  double least_strain = 0;
  while (sim.bonds_broken() == 0 && sim.time() < axial.period()) {
    sim.step();
    if (sim.bonds().size() == 1) least_strain = std::min(least_strain, sim.bonds().force[0].dot(kPairAxis) / (b.axial() * b.l0));
  }
  std::printf("thrown pair: least strain %.3f, broke at t = %.3g T\n", least_strain, sim.time() / axial.period());
  CHECK(least_strain < -0.45);
  REQUIRE(sim.break_events().size() == 1);
  const BondBreakEvent& e = sim.break_events().front();
  CHECK(e.time > 0.5 * axial.period());  // the whole compressive half cycle survived
  CHECK(e.stress.dominant == BondFailureMode::Tension);
  CHECK(e.stress.tension >= p.critical_stress);
}

namespace {

// Eight spheres on a slightly distorted 2 x 2 x 2 block with its 12 edges and 2 face diagonals
// bonded, thrown apart hard enough that some bonds fail.
SimulationSetup block(const BondModel& model, bool swap_bonds) {
  SimulationSetup s;
  const double l0 = 2 * kRadius;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner((k & 1) ? l0 : 0, (k & 2) ? l0 : 0, (k & 4) ? l0 : 0);
    s.particles.add(corner + 0.02 * l0 * Vec3(u(rng), u(rng), u(rng)), kRadius, kDensity);
    s.particles.orientation[k] = rotation(Vec3(u(rng), u(rng), u(rng)));
    s.particles.velocity[k] = 1.5 * Vec3(u(rng), u(rng), u(rng));      // m/s
    s.particles.omega[k] = 3000 * Vec3(u(rng), u(rng), u(rng));        // rad/s
  }
  for (Index a = 0; a < 8; ++a)
    for (int bit : {1, 2, 4})
      if (!(a & bit)) s.bonds.emplace_back(a, a | bit);
  s.bonds.emplace_back(0, 3);
  s.bonds.emplace_back(4, 7);
  if (swap_bonds)
    for (auto& [i, j] : s.bonds) std::swap(i, j);
  s.bond = &model;
  return s;
}

}  // namespace

TEST_CASE("swapping the two particles of every bond gives the same trajectory and the same breaks") {
  const BeamPlugin beam({{"damping", 1e-4}});  // default eq. 6 damping, breakage on
  Simulation forward(block(beam.model(), false));
  Simulation swapped(block(beam.model(), true));
  // The bond model orders each bond's ends by stable id, which makes `swapped` run identical
  // arithmetic. Reversed ids make the model lead with the other particle of every bond: the
  // mirrored bond frame and other rounding, the same physics.
  SimulationSetup mirrored_setup = block(beam.model(), true);
  for (std::size_t k = 0; k < 8; ++k) mirrored_setup.particles.id[k] = static_cast<Index>(7 - k);
  Simulation mirrored(std::move(mirrored_setup));
  const std::int64_t steps = 4000;
  forward.run(steps);
  swapped.run(steps);
  mirrored.run(steps);

  const double l0 = 2 * kRadius;
  CHECK(forward.bonds_broken() > 0);  // the comparison covers breakage too
  for (const Simulation* other : {&swapped, &mirrored}) {
    const bool ids_reversed = other == &mirrored;
    double worst_position = 0, worst_rotation = 0;
    for (std::size_t k = 0; k < 8; ++k) {
      worst_position = std::max(worst_position, (forward.particles().position[k] - other->particles().position[k]).norm() / l0);
      worst_rotation = std::max(worst_rotation, forward.particles().orientation[k].angularDistance(other->particles().orientation[k]));
    }
    std::printf("%s: %lld of 14 broke; largest difference %.2e l0, %.2e rad\n",
                ids_reversed ? "swapped bonds, reversed ids" : "swapped bonds", static_cast<long long>(other->bonds_broken()),
                worst_position, worst_rotation);
    CAPTURE(ids_reversed);
    CHECK(worst_position < 1e-9);
    CHECK(worst_rotation < 1e-9);
    REQUIRE(forward.break_events().size() == other->break_events().size());
    for (std::size_t k = 0; k < forward.break_events().size(); ++k) {
      const BondBreakEvent& a = forward.break_events()[k];
      const BondBreakEvent& b = other->break_events()[k];
      auto index_of = [&](Index id) { return ids_reversed ? 7 - id : id; };
      CHECK(a.step == b.step);
      CHECK(std::minmax(a.id_i, a.id_j) == std::minmax(index_of(b.id_i), index_of(b.id_j)));
      CHECK(a.stress.sigma_vm == doctest::Approx(b.stress.sigma_vm).epsilon(1e-9));
      CHECK(a.stress.dominant == b.stress.dominant);
    }
  }
}
