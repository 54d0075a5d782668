#include <doctest/doctest.h>

#include "shard/simulation.hpp"

using namespace shard;

TEST_CASE("free fall follows x0 + v0 t + g t^2 / 2") {
  SimulationSetup setup;
  setup.particles.add(Vec3(0.1, -0.2, 3.0), 0.01, 2500.0);
  setup.particles.velocity[0] = Vec3(0.5, 0.0, 2.0);
  setup.particles.omega[0] = Vec3(0.0, 30.0, 0.0);
  setup.gravity = Vec3(0, 0, -9.81);
  setup.dt = 1e-4;
  Simulation sim(std::move(setup));
  sim.run(10000);
  const double t = sim.time();
  CHECK(t == doctest::Approx(1.0).epsilon(1e-12));
  const Vec3 expected = Vec3(0.1, -0.2, 3.0) + Vec3(0.5, 0.0, 2.0) * t + 0.5 * Vec3(0, 0, -9.81) * t * t;
  // Velocity Verlet is exact for a constant force; what remains is round-off.
  CHECK((sim.particles().position[0] - expected).norm() / expected.norm() < 1e-9);
  CHECK((sim.particles().velocity[0] - Vec3(0.5, 0, 2.0 - 9.81 * t)).norm() < 1e-9);
  // A free sphere keeps spinning at constant rate; its orientation turned by omega t about y.
  const Quat expected_q(Eigen::AngleAxisd(30.0 * t, Vec3::UnitY()));
  CHECK(sim.particles().orientation[0].angularDistance(expected_q) < 1e-9);
  CHECK(std::abs(sim.particles().orientation[0].norm() - 1.0) < 1e-12);
}

TEST_CASE("a fixed particle does not move under gravity") {
  SimulationSetup setup;
  setup.particles.add(Vec3(0, 0, 1), 0.01, 2500.0);
  setup.particles.flags[0] = kFixed;
  setup.gravity = Vec3(0, 0, -9.81);
  setup.dt = 1e-4;
  Simulation sim(std::move(setup));
  sim.run(100);
  CHECK(sim.particles().position[0] == Vec3(0, 0, 1));
  CHECK(sim.particles().force[0].z() == doctest::Approx(-9.81 * sim.particles().mass[0]).scale(0));
}

TEST_CASE("auto time step needs a model") {
  SimulationSetup setup;
  setup.particles.add(Vec3(0, 0, 0), 0.01, 2500.0);
  CHECK_THROWS_WITH_AS(Simulation(std::move(setup)), doctest::Contains("needs a contact or bond model"),
                       std::invalid_argument);
}
