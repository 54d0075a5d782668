// [simulation] bonded_contacts = false: a pair joined by an intact bond feels its bond alone, and
// its contact starts once the bond has failed. Two spheres of radius R overlapping by delta, bonded
// in that position (so the bond carries no load at rest), with a linear spring k_n and e = 1 (no
// dashpot): the contact force, where there is one, is k_n delta to round-off.
#include <doctest/doctest.h>

#include <cmath>

#include "kernel_fixtures.hpp"

using namespace shard;

namespace {

constexpr double kRadius = 1e-3, kOverlap = 1e-5, kStiffness = 1e4;

std::unique_ptr<BondModel> beam_bond(double critical_stress) {
  auto& host = test::plugins();
  return host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond",
                                                 {{"youngs_modulus", 1e8}, {"critical_stress", critical_stress}}));
}

// The bonded pair on the x axis; `speed` m/s each, apart.
SimulationSetup bonded_pair(const ContactModel& contact, const BondModel& bond, bool bonded_contacts, double speed) {
  SimulationSetup setup;
  setup.particles.add(Vec3(0, 0, 0), kRadius, 2500.0);
  setup.particles.add(Vec3(2 * kRadius - kOverlap, 0, 0), kRadius, 2500.0);
  setup.particles.velocity[0] = Vec3(-speed, 0, 0);
  setup.particles.velocity[1] = Vec3(speed, 0, 0);
  setup.bonds = {{0, 1}};
  setup.contact = &contact;
  setup.bond = &bond;
  setup.bonded_contacts = bonded_contacts;
  setup.dt = 1e-8;
  return setup;
}

double overlap_of(const Simulation& sim) {
  const Particles& p = sim.particles();
  return p.radius[0] + p.radius[1] - (p.position[1] - p.position[0]).norm();
}

}  // namespace

TEST_CASE("a bonded overlapping pair gets a contact force unless bonded_contacts is off") {
  const auto contact = test::linear_spring(kStiffness, 1.0, 0.5);
  const auto bond = beam_bond(1e12);  // never fails here
  for (const bool bonded_contacts : {true, false}) {
    CAPTURE(bonded_contacts);
    Simulation sim(bonded_pair(*contact, *bond, bonded_contacts, 0.0));
    // The first force pass, at rest in the bond's own position: the bond pulls with nothing, so any
    // force is the contact's. Off, nothing ever moves; on, the contact pushes the pair apart
    // against the bond.
    const double force = sim.particles().force[0].norm();
    if (bonded_contacts)
      CHECK(force == doctest::Approx(kStiffness * kOverlap).epsilon(1e-9));
    else
      CHECK(force < 1e-9 * kStiffness * kOverlap);
    for (int s = 0; s < 3; ++s) {
      CHECK(sim.contact_count() == (bonded_contacts ? 1u : 0u));
      sim.step();
    }
    if (!bonded_contacts) CHECK(sim.particles().force[0].norm() < 1e-9 * kStiffness * kOverlap);
    CHECK(sim.bonds().size() == 1);
  }
}

TEST_CASE("with bonded_contacts off, a pair's contact starts when its bond breaks") {
  const auto contact = test::linear_spring(kStiffness, 1.0, 0.5);
  const auto bond = beam_bond(1.0);  // 1 Pa: fails as soon as the ends move apart
  Simulation sim(bonded_pair(*contact, *bond, false, 1e-3));
  CHECK(sim.contact_count() == 0);
  int steps = 0;
  while (sim.bonds().size() == 1 && steps < 10) {
    CHECK(sim.contact_count() == 0);  // bonded: the bond alone
    sim.step();
    ++steps;
  }
  REQUIRE(sim.bonds().size() == 0);
  // The force pass in which the bond failed still ran without the pair; from the next one on, the
  // pair is listed and, still overlapping, pushed apart by k_n delta.
  sim.step();
  REQUIRE(overlap_of(sim) > 0.5 * kOverlap);
  CHECK(sim.contact_count() == 1);
  const Particles& p = sim.particles();
  CHECK(p.force[1].x() == doctest::Approx(kStiffness * overlap_of(sim)).epsilon(1e-6).scale(0));
  CHECK(p.force[0].x() == doctest::Approx(-kStiffness * overlap_of(sim)).epsilon(1e-6).scale(0));
}
