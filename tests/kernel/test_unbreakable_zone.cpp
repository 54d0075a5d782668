// [[wall]] unbreakable_zone: the bonds between particles that start within that distance of a
// wall's surface never fail; a bond with one end outside the zone fails as any other.
#include <doctest/doctest.h>

#include "kernel_fixtures.hpp"
#include "shard/unbreakable_zone.hpp"

using namespace shard;

namespace {

constexpr double kRadius = 1e-3;

Wall roller_along_y(double zone) {
  Wall w;
  w.name = "support";
  w.shape = WallShape::Cylinder;
  w.point = Vec3(0, 0, 0);
  w.axis = Vec3::UnitY();
  w.radius = 5e-3;
  w.length = 0.02;
  w.unbreakable_zone = zone;
  return w;
}

// Two bonded spheres moving apart at 1 mm/s each; the first `flagged` of them in a zone.
SimulationSetup pulled_pair(const ContactModel& contact, const BondModel& bond, int flagged) {
  SimulationSetup setup;
  setup.particles.add(Vec3(0, 0, 0), kRadius, 2500.0);
  setup.particles.add(Vec3(2 * kRadius, 0, 0), kRadius, 2500.0);
  setup.particles.velocity[0] = Vec3(-1e-3, 0, 0);
  setup.particles.velocity[1] = Vec3(1e-3, 0, 0);
  for (int k = 0; k < flagged; ++k) setup.particles.flags[static_cast<std::size_t>(k)] |= kUnbreakable;
  setup.bonds = {{0, 1}};
  setup.contact = &contact;
  setup.bond = &bond;
  setup.dt = 1e-8;
  return setup;
}

}  // namespace

TEST_CASE("a wall's unbreakable zone holds the particles whose centres start within it of the surface") {
  Particles p;
  p.add(Vec3(0, 0, 5e-3 + 2e-3), kRadius, 2500.0);    // 2 mm above the roller's top
  p.add(Vec3(0, 0, 5e-3 + 4e-3), kRadius, 2500.0);    // 4 mm above it
  p.add(Vec3(0, 0.05, 5e-3 + 1e-3), kRadius, 2500.0);  // beyond the roller's end
  const auto marked = mark_unbreakable_zones(p, {roller_along_y(3e-3), roller_along_y(0)});
  CHECK(marked == std::vector<std::size_t>{1, 0});
  CHECK((p.flags[0] & kUnbreakable) != 0);
  CHECK((p.flags[1] & kUnbreakable) == 0);
  CHECK((p.flags[2] & kUnbreakable) == 0);
}

TEST_CASE("a bond fails unless both of its particles lie in an unbreakable zone") {
  const auto contact = test::linear_spring(1e4, 1.0, 0.5);
  auto& host = test::plugins();
  // 1 Pa: the bond fails as soon as its ends move apart.
  const auto bond = host.make_bond(
      "beam_bond", host.params(PluginKind::Bond, "beam_bond", {{"youngs_modulus", 1e8}, {"critical_stress", 1.0}}));
  for (const int flagged : {0, 1, 2}) {
    CAPTURE(flagged);
    Simulation sim(pulled_pair(*contact, *bond, flagged));
    for (int s = 0; s < 20; ++s) sim.step();
    CHECK(sim.bonds().size() == (flagged == 2 ? 1u : 0u));
    // The kept bond still pulls the pair back together: it transmits its load as an intact bond.
    if (flagged == 2) CHECK(sim.particles().force[0].x() > 0);
  }
}
