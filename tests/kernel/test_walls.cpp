#include <doctest/doctest.h>

#include "kernel_fixtures.hpp"

using namespace shard;

namespace {
// A sphere that comes to rest on a wall: the wall's force sensor must read the sphere's weight.
std::unique_ptr<Simulation> settle_on(Wall wall, const Vec3& start, const ContactModel& model) {
  SimulationSetup setup;
  setup.particles.add(start, 0.005, 2500.0);
  setup.walls.push_back(std::move(wall));
  setup.gravity = Vec3(0, 0, -9.81);
  setup.contact = &model;
  setup.dt = 1e-5;
  auto sim = std::make_unique<Simulation>(std::move(setup));
  sim->run(100000);
  return sim;
}
}  // namespace

TEST_CASE("a resting sphere loads a plane wall with its weight at overlap m g / k") {
  auto model = test::linear_spring(1e4, 0.3, 0.5);
  Wall plane;
  plane.shape = WallShape::Plane;
  plane.axis = Vec3::UnitZ();
  auto owned = settle_on(plane, Vec3(0, 0, 0.005), *model);
  const Simulation& sim = *owned;
  const double weight = sim.particles().mass[0] * 9.81;
  CHECK(sim.walls()[0].force.z() == doctest::Approx(-weight).epsilon(1e-6).scale(0));
  const double overlap = 0.005 - sim.particles().position[0].z();
  CHECK(overlap == doctest::Approx(weight / 1e4).epsilon(0.01).scale(0));
}

TEST_CASE("a sphere resting on top of a cylinder pin loads it with its weight") {
  auto model = test::linear_spring(1e4, 0.3, 0.5);
  Wall pin;
  pin.shape = WallShape::Cylinder;
  pin.axis = Vec3::UnitY();
  pin.radius = 0.01;
  pin.length = 0.05;
  auto owned = settle_on(pin, Vec3(0, 0, 0.015), *model);
  const Simulation& sim = *owned;
  const double weight = sim.particles().mass[0] * 9.81;
  CHECK(sim.walls()[0].force.z() == doctest::Approx(-weight).epsilon(1e-6).scale(0));
  CHECK(std::abs(sim.walls()[0].force.x()) < 1e-9 * weight);
  const double overlap = 0.015 - sim.particles().position[0].z();
  CHECK(overlap == doctest::Approx(weight / 1e4).epsilon(0.01).scale(0));
}

TEST_CASE("a moving wall's displacement is velocity times time") {
  auto model = test::linear_spring();
  SimulationSetup setup;
  setup.particles.add(Vec3(0, 0, 1), 0.005, 2500.0);
  Wall w;
  w.shape = WallShape::Plane;
  w.axis = Vec3::UnitZ();
  w.velocity = Vec3(0, 0, 0.2);
  setup.walls.push_back(w);
  setup.contact = model.get();
  setup.dt = 1e-4;
  Simulation sim(std::move(setup));
  sim.run(1000);
  CHECK(sim.walls()[0].displacement.z() == doctest::Approx(0.02).epsilon(1e-12));
}
