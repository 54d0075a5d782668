#include <doctest/doctest.h>

#include <set>

#include "kernel_fixtures.hpp"

using namespace shard;

TEST_CASE("the Verlet list finds exactly the touching pairs a brute-force search finds") {
  auto model = test::linear_spring(1e3, 0.9, 0.3);
  SimulationSetup setup;
  const double side = 0.1, radius = 0.006;
  setup.particles = test::random_gas(1000, side, radius, 7);
  for (auto& v : setup.particles.velocity) v *= 2.0;  // dense, fast gas: many rebuilds
  setup.walls = test::box_walls(side);
  setup.contact = model.get();
  setup.dt = 2e-5;
  Simulation sim(std::move(setup));
  for (int round = 0; round < 5; ++round) {
    sim.run(400);
    const auto& p = sim.particles();
    std::size_t brute = 0;
    for (std::size_t a = 0; a < p.size(); ++a) {
      for (std::size_t b = a + 1; b < p.size(); ++b)
        if ((p.position[a] - p.position[b]).norm() < p.radius[a] + p.radius[b]) ++brute;
      for (const auto& w : sim.walls()) {
        Vec3 n;
        double d;
        if (wall_contact(w, p.position[a], p.radius[a], n, d) && d < p.radius[a]) ++brute;
      }
    }
    CHECK(sim.contact_count() == brute);
  }
  CHECK(sim.neighbour_rebuilds() > 5);
}

TEST_CASE("contact history survives neighbour-list rebuilds") {
  // A sphere held on a plane by gravity and dragged sideways by a moving plane wall underneath:
  // the tangential spring must keep loading through rebuilds until it reaches mu F_n.
  auto model = test::linear_spring(1e5, 0.5, 0.4);
  SimulationSetup setup;
  setup.particles.add(Vec3(0, 0, 0.01 - 1e-6), 0.01, 2500.0);
  Wall floor;
  floor.shape = WallShape::Plane;
  floor.axis = Vec3::UnitZ();
  floor.velocity = Vec3(0.05, 0, 0);
  setup.walls.push_back(floor);
  setup.gravity = Vec3(0, 0, -9.81);
  setup.particles.flags[0] = 0;
  setup.contact = model.get();
  setup.skin = 1e-4;  // tiny skin: the moving wall forces frequent rebuilds
  setup.dt = 1e-6;
  Simulation sim(std::move(setup));
  sim.run(200000);
  CHECK(sim.neighbour_rebuilds() > 20);
  // Dragged at 5 cm/s, the sphere is carried along (static friction, rolling): it keeps touching.
  CHECK(sim.contact_count() == 1);
  CHECK(sim.particles().velocity[0].x() > 0.01);
}
