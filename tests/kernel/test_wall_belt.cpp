// Conveyor belts: a wall whose surface slides over its fixed geometry carries what lies on it.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "kernel_fixtures.hpp"
#include "wall_spin_fixtures.hpp"

using namespace shard;

namespace {

constexpr double kRadius = 0.005, kDensity = 2500.0, kMu = 0.5, kG = 9.81, kBelt = 0.2;

// The rest overlap of a sphere of kRadius on a spring of 1e4 N/m, m g / k.
double rest_overlap() { return kDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3) * kG / 1e4; }

Wall flat_belt(bool as_mesh) {
  Wall w;
  if (as_mesh) {  // a 0.4 m x 0.2 m rectangle in z = 0
    w.shape = WallShape::Mesh;
    const Vec3 a(-0.2, -0.1, 0), b(0.2, -0.1, 0), c(0.2, 0.1, 0), d(-0.2, 0.1, 0);
    w.triangles = {{a, b, c}, {a, c, d}};
  } else {
    w.shape = WallShape::Plane;
    w.axis = Vec3::UnitZ();
  }
  w.surface_velocity = Vec3(kBelt, 0, 0);
  return w;
}

}  // namespace

TEST_CASE("a bonded body set on a belt slides at mu g t, then rides at the belt speed") {
  auto model = test::linear_spring(1e4, 0.5, kMu);
  auto& host = test::plugins();
  auto bond = host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", {{"damping", 0.5}}));
  for (bool as_mesh : {false, true}) {
    CAPTURE(as_mesh);
    SimulationSetup setup;
    // Two bonded spheres along the belt, at their rest overlap and at rest: the belt slides under
    // them from the first step.
    const double z = kRadius - rest_overlap();
    setup.particles.add(Vec3(-kRadius, 0, z), kRadius, kDensity);
    setup.particles.add(Vec3(kRadius, 0, z), kRadius, kDensity);
    setup.bonds.push_back({0, 1});
    setup.bond = bond.get();
    setup.walls.push_back(flat_belt(as_mesh));
    setup.gravity = Vec3(0, 0, -kG);
    setup.contact = model.get();
    setup.dt = 1e-5;
    Simulation sim(std::move(setup));
    auto body_speed = [&] { return 0.5 * (sim.particles().velocity[0].x() + sim.particles().velocity[1].x()); };
    // Sliding, Coulomb friction mu m g accelerates the body at mu g = 4.9 m/s^2 until it reaches
    // the belt at t* = V / (mu g) = 41 ms. At 20 ms it is half way. The body rests at its
    // equilibrium overlap, so the normal force is m g and the capped friction mu m g from the
    // first step (the tangential spring saturates within it at 0.2 m/s): v = mu g t to round-off
    // (4e-14 measured); 1e-9 allowed.
    sim.run(2000);
    CHECK(body_speed() == doctest::Approx(kMu * kG * sim.time()).epsilon(1e-9));
    // Long after t*: sticking, the body moves with the belt; the springs' ringing after the switch
    // from sliding to sticking is damped (restitution 0.5 on both springs) well within 60 ms.
    sim.run(10000);
    CHECK(body_speed() == doctest::Approx(kBelt).epsilon(1e-3).scale(0));
    CHECK(std::abs(sim.particles().velocity[0].y()) < 1e-9);  // nothing pushes it sideways
    // The belt's geometry stayed put: only its surface moved.
    CHECK(sim.walls()[0].displacement.norm() == 0.0);
  }
}

TEST_CASE("a free sphere set on a belt ends rolling at 2/7 of the belt speed") {
  // Friction acts at the contact line, so the sphere's angular momentum about a line on the belt
  // stays zero: m v r = I w with rolling v + w r = V gives v = V I / (I + m r^2) = 2 V / 7 for a
  // solid sphere. The relative velocity at the contact (v + omega x arm - belt) carries the spin.
  auto model = test::linear_spring(1e4, 0.5, kMu);
  SimulationSetup setup;
  setup.particles.add(Vec3(0, 0, kRadius - rest_overlap()), kRadius, kDensity);
  setup.walls.push_back(flat_belt(false));
  setup.gravity = Vec3(0, 0, -kG);
  setup.contact = model.get();
  setup.dt = 1e-5;
  Simulation sim(std::move(setup));
  sim.run(10000);  // 0.1 s; the slip ends at t = 2 V / (7 mu g) = 12 ms
  // 0.5 %: the tangential spring's stretch at the end of the slip rings down, damped.
  CHECK(sim.particles().velocity[0].x() == doctest::Approx(2.0 / 7.0 * kBelt).epsilon(5e-3).scale(0));
  CHECK(sim.particles().omega[0].y() * kRadius == doctest::Approx(-5.0 / 7.0 * kBelt).epsilon(5e-3).scale(0));
}
