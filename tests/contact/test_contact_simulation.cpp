// The contact plugins inside the kernel's step loop (shard::Simulation): walls, gravity, torque.
#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>

#include "contact_arrays.hpp"
#include "contact_plugins.hpp"
#include "shard/simulation.hpp"
#include "table_one.hpp"

using namespace shard;
using namespace shard::test;

namespace {

Wall floor_plane() {
  Wall w;
  w.name = "floor";
  w.shape = WallShape::Plane;
  w.point = Vec3::Zero();
  w.axis = Vec3::UnitZ();
  return w;
}

const Vec3 gravity(0.0, 0.0, -9.81);

}  // namespace

TEST_CASE("linear_spring: a sphere resting on a plane settles at overlap m g / k_n") {
  const ContactPlugins plugins;
  const double k_n = 1e3;
  const auto model = plugins.make("linear_spring", {{"normal_stiffness", k_n}, {"restitution", 0.3}});
  const double r = 1e-3;
  SimulationSetup setup;
  setup.particles.add(Vec3(0.0, 0.0, r), r, table_one::density);  // touching, at rest
  setup.walls.push_back(floor_plane());
  setup.gravity = gravity;
  setup.contact = model.get();
  Simulation sim(std::move(setup));
  const double m = sim.particles().mass[0];
  // Damping ratio 0.5 (e = 0.3): the oscillation decays as exp(-zeta omega t), omega =
  // sqrt(k_n / m) = 8.0e3 rad/s; 0.01 s is 40 decay times.
  const auto steps = static_cast<std::int64_t>(std::ceil(0.01 / sim.dt()));
  sim.run(steps);
  const double overlap = r - sim.particles().position[0].z();
  const double expected = m * 9.81 / k_n;
  MESSAGE("settled overlap " << overlap << " m, m g / k_n = " << expected << " m, after " << steps << " steps");
  CHECK(std::abs(overlap - expected) <= 0.01 * expected);
  CHECK(sim.particles().velocity[0].norm() <= 1e-3 * 9.81 * std::sqrt(m / k_n));
  // The floor is a force sensor: it carries the weight.
  CHECK(std::abs(sim.walls()[0].force.z() + m * 9.81) <= 0.01 * m * 9.81);
  CHECK(sim.contact_count() == 1);
}

TEST_CASE("hertz_mindlin: head-on collision in the simulation realises the set restitution") {
  const ContactPlugins plugins;
  const double e = 0.5;
  const auto model = plugins.make("hertz_mindlin", {{"restitution", e}});
  const double r = table_one::radius;
  const double v0 = 0.1;  // approach speed, m/s
  SimulationSetup setup;
  const Index a = setup.particles.add(Vec3(-r - 1e-6, 0.0, 0.0), r, table_one::density);
  const Index b = setup.particles.add(Vec3(r + 1e-6, 0.0, 0.0), r, table_one::density);
  setup.particles.velocity[static_cast<std::size_t>(a)] = Vec3(0.5 * v0, 0.0, 0.0);
  setup.particles.velocity[static_cast<std::size_t>(b)] = Vec3(-0.5 * v0, 0.0, 0.0);
  setup.contact = model.get();  // dt = auto: 0.2 t_Rayleigh
  Simulation sim(std::move(setup));
  CHECK(sim.dt() == doctest::Approx(0.2 * 2.31176e-5).epsilon(1e-5).scale(0));
  bool touched = false;
  std::int64_t steps_in_contact = 0;
  for (int step = 0; step < 100000; ++step) {
    sim.step();
    if (sim.contact_count() > 0) {
      touched = true;
      ++steps_in_contact;
    } else if (touched) {
      break;
    }
  }
  REQUIRE(touched);
  const auto& v = sim.particles().velocity;
  const double separation_speed = v[1].x() - v[0].x();
  MESSAGE("realised restitution " << separation_speed / v0 << " over " << steps_in_contact << " steps");
  CHECK(std::abs(separation_speed / v0 - e) <= 0.02 * e);
  // Momentum is conserved exactly and nothing leaves the line of centres.
  CHECK(std::abs(v[0].x() + v[1].x()) <= 1e-12 * v0);
  CHECK(v[0].tail<2>().norm() == 0.0);
}

TEST_CASE("hertz_mindlin: a sphere launched sliding on a plane ends rolling at 5/7 of its speed") {
  // Friction decelerates the centre and spins the sphere up until the contact point sticks;
  // angular momentum about the contact point is conserved, so the rolling speed is
  // v0 m r^2 / (m r^2 + I) = 5/7 v0 whatever mu and the tangential spring are.
  const ContactPlugins plugins;
  const auto model = plugins.make("hertz_mindlin", {{"restitution", 0.3}});
  const double r = 1e-3;
  const double v0 = 0.1;
  SimulationSetup setup;
  setup.particles.add(Vec3(0.0, 0.0, r), r, table_one::density);
  setup.particles.velocity[0] = Vec3(v0, 0.0, 0.0);
  setup.walls.push_back(floor_plane());
  setup.gravity = gravity;
  setup.contact = model.get();
  Simulation sim(std::move(setup));
  // Sliding ends after 2 v0 / (7 mu g) = 4.3 ms; run 30 ms.
  sim.run(static_cast<std::int64_t>(std::ceil(0.03 / sim.dt())));
  const auto& p = sim.particles();
  MESSAGE("rolling speed " << p.velocity[0].x() << " m/s, 5/7 v0 = " << 5.0 / 7.0 * v0);
  CHECK(std::abs(p.velocity[0].x() - 5.0 / 7.0 * v0) <= 0.01 * 5.0 / 7.0 * v0);
  // Rolling without slip: v = omega_y r (to the contact's arm, r minus the overlap).
  CHECK(std::abs(p.omega[0].y() * r - p.velocity[0].x()) <= 0.01 * p.velocity[0].x());
}

TEST_CASE("hertz_mindlin: an elastic collision conserves kinetic plus contact energy") {
  // e = 1 and no friction: the stored energy 8/15 E* sqrt(R*) delta^2.5 must be the work of the
  // force; with 200+ steps per contact velocity Verlet keeps the sum to 1e-5 (measured 8.8e-6).
  const ContactPlugins plugins;
  const auto model = plugins.make("hertz_mindlin", {{"restitution", 1.0}, {"friction", 0.0}});
  const double r = table_one::radius;
  SimulationSetup setup;
  setup.particles.add(Vec3(-r, 0.0, 0.0), r, table_one::density);
  setup.particles.add(Vec3(r, 0.0, 0.0), r, table_one::density);
  setup.particles.velocity[0] = Vec3(0.05, 0.0, 0.0);
  setup.particles.velocity[1] = Vec3(-0.05, 0.0, 0.0);
  setup.contact = model.get();
  setup.dt = 2.31176e-5 / 100;
  Simulation sim(std::move(setup));
  const double e0 = sim.energies().kinetic;
  double worst = 0.0, peak_contact = 0.0;
  for (int step = 0; step < 2000; ++step) {
    sim.step();
    const Energies e = sim.energies();
    worst = std::fmax(worst, std::abs(e.kinetic + e.contact - e0));
    peak_contact = std::fmax(peak_contact, e.contact);
  }
  MESSAGE("largest energy error " << worst / e0 << " of the kinetic energy; peak contact energy " << peak_contact / e0);
  CHECK(peak_contact >= 0.9 * e0);  // the collision happened and stored nearly everything
  CHECK(worst <= 1e-4 * e0);
  CHECK(sim.contact_count() == 0);
  CHECK(std::abs(sim.energies().kinetic - e0) <= 1e-4 * e0);
}
