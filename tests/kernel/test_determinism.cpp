#include <doctest/doctest.h>

#include "kernel_fixtures.hpp"

using namespace shard;

namespace {
Particles run_gas(int threads_hint) {
  (void)threads_hint;
  auto model = test::linear_spring(1e3, 0.7, 0.5);
  SimulationSetup setup;
  setup.particles = test::random_gas(512, 0.08, 0.005, 11);
  setup.walls = test::box_walls(0.08);
  setup.gravity = Vec3(0, 0, -9.81);
  setup.contact = model.get();
  setup.dt = 2e-5;
  Simulation sim(std::move(setup));
  sim.run(3000);
  return sim.particles();
}
}  // namespace

TEST_CASE("the same scene twice gives bit-identical final states") {
  const Particles a = run_gas(1);
  const Particles b = run_gas(1);
  REQUIRE(a.size() == b.size());
  bool identical = true;
  for (std::size_t k = 0; k < a.size(); ++k) {
    identical = identical && a.position[k] == b.position[k] && a.velocity[k] == b.velocity[k] &&
                a.omega[k] == b.omega[k] && a.orientation[k].coeffs() == b.orientation[k].coeffs();
  }
  CHECK(identical);
}
