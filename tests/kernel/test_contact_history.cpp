// The contact pass reads a per-pair "touching" byte instead of the history of every listed pair
// and zeroes a history only when that byte says the pair touched at the last pass. These tests
// check what that relies on: the byte follows its pair through rebuilds and renumbering (a pair
// that stops touching is still found and zeroed), and a restored list, which carries no byte,
// continues bit for bit.
#include <doctest/doctest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "kernel_fixtures.hpp"
#include "shard/checkpoint.hpp"

using namespace shard;

namespace {

// Elastic (e = 1): a contact separates with its normal force, hence its friction spring, still
// loaded. With a dashpot the force is clamped to zero before the spheres part, and the spring
// with it, so a history the kernel failed to zero would be zero anyway and go unseen.
std::unique_ptr<ContactModel> elastic_spring() { return test::linear_spring(1e3, 1.0, 0.5); }

// Above the kernel's renumbering threshold (1e4), so the particles are renumbered at rebuilds.
SimulationSetup colliding_gas(const ContactModel& model) {
  SimulationSetup setup;
  const double side = 0.1;
  setup.particles = test::random_gas(12000, side, 0.0021, 5);
  setup.walls = test::box_walls(side);
  setup.gravity = Vec3(0, 0, -9.81);
  setup.contact = &model;
  setup.dt = 2e-5;
  return setup;
}

// The kernel's own touching test (simulation.cpp), so a pair at the boundary counts the same.
bool touching(const SimulationState& s, const std::vector<Wall>& walls, std::size_t k) {
  const Particles& p = s.particles;
  const auto a = static_cast<std::size_t>(s.neighbours.first[k]);
  const Index b = s.neighbours.second[k];
  if (b < 0) {
    Vec3 n;
    double d;
    return wall_contact(walls[static_cast<std::size_t>(-1 - b)], p.position[a], p.radius[a], n, d) && d < p.radius[a];
  }
  const double dist2 = (p.position[a] - p.position[static_cast<std::size_t>(b)]).squaredNorm();
  const double reach = p.radius[a] + p.radius[static_cast<std::size_t>(b)];
  return !(dist2 >= reach * reach || dist2 == 0.0);
}

bool same_state(const Particles& a, const Particles& b) {
  bool same = a.size() == b.size();
  for (std::size_t k = 0; same && k < a.size(); ++k)
    same = a.id[k] == b.id[k] && a.position[k] == b.position[k] && a.velocity[k] == b.velocity[k] &&
           a.omega[k] == b.omega[k] && a.orientation[k].coeffs() == b.orientation[k].coeffs();
  return same;
}

}  // namespace

TEST_CASE("a listed pair that is not touching has zero history, through rebuilds and renumbering") {
  auto model = elastic_spring();
  Simulation sim(colliding_gas(*model));
  std::size_t with_history = 0, released = 0, zero_violations = 0;
  std::vector<std::pair<Index, Index>> was_pairs;  // touching at the previous check, by stable ids
  for (int round = 0; round < 15; ++round) {
    sim.run(20);
    const SimulationState s = sim.export_state();
    const std::size_t stride = s.neighbours.history_stride;
    REQUIRE(stride > 0);
    std::vector<std::pair<Index, Index>> now_pairs;
    for (std::size_t k = 0; k < s.neighbours.first.size(); ++k) {
      bool zero = true;
      for (std::size_t q = 0; q < stride; ++q) zero = zero && s.neighbours.history[k * stride + q] == 0.0;
      if (touching(s, sim.walls(), k)) {
        with_history += zero ? 0 : 1;
        const Index b = s.neighbours.second[k];
        now_pairs.emplace_back(s.particles.id[static_cast<std::size_t>(s.neighbours.first[k])],
                               b < 0 ? b : s.particles.id[static_cast<std::size_t>(b)]);
      } else {
        zero_violations += zero ? 0 : 1;
      }
    }
    std::sort(now_pairs.begin(), now_pairs.end());
    for (const auto& pair : was_pairs) released += std::binary_search(now_pairs.begin(), now_pairs.end(), pair) ? 0 : 1;
    was_pairs = std::move(now_pairs);
  }
  CHECK(zero_violations == 0);
  // The run must exercise what the byte is for: contacts with a history that then separate,
  // list rebuilds and renumbered particles.
  CHECK(with_history > 100);
  CHECK(released > 100);
  CHECK(sim.neighbour_rebuilds() > 5);
  bool renumbered = false;
  for (std::size_t k = 0; k < sim.particles().size(); ++k) renumbered = renumbered || sim.particles().id[k] != static_cast<Index>(k);
  CHECK(renumbered);
}

TEST_CASE("a list restored from a state, whose touching bytes are derived, continues bit for bit") {
  auto model = elastic_spring();
  Simulation uninterrupted(colliding_gas(*model));
  uninterrupted.run(150);
  const SimulationState middle = uninterrupted.export_state();
  Simulation restarted(colliding_gas(*model));
  restarted.import_state(middle);
  uninterrupted.run(150);
  restarted.run(150);
  CHECK(uninterrupted.contact_count() == restarted.contact_count());
  CHECK(same_state(uninterrupted.particles(), restarted.particles()));
}
