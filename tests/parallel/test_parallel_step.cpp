// A cubic block of 22 x 22 x 21 = 10164 bonded spheres (above the kernel's renumbering threshold
// of 1e4) squeezed between two slabs of kPrescribed particles: bonds, Hertz-Mindlin contacts with
// tangential history, neighbour rebuilds and Morton renumbering all take part.
#include <doctest/doctest.h>
#include <omp.h>

#include <algorithm>
#include <map>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

#include "../common/beam_hertz_models.hpp"
#include "shard/plugin_host.hpp"
#include "shard/simulation.hpp"

using namespace shard;

namespace {

constexpr int kNx = 22, kNy = 22, kNz = 21;
constexpr double kD = 1e-3;        // m, diameter and lattice spacing
constexpr double kSpeed = 0.2;     // m/s, each slab
constexpr std::int64_t kSteps = 250;

using Models = testing::BeamHertzModels;

Models& models() {
  static Models m;
  return m;
}

// The block with its particles listed in `order` (a permutation of the lattice numbering); the
// stable id is the lattice number, so runs with different listings can be compared by id.
SimulationSetup block(const std::vector<Index>& order) {
  const auto site = [](int x, int y, int z) { return static_cast<Index>((z * kNy + y) * kNx + x); };
  std::vector<Index> slot(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) slot[static_cast<std::size_t>(order[k])] = static_cast<Index>(k);
  SimulationSetup s;
  s.particles.reserve(order.size());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jitter(-0.02 * kD, 0.02 * kD);
  std::vector<Vec3> x(order.size());
  for (int z = 0; z < kNz; ++z)
    for (int y = 0; y < kNy; ++y)
      for (int i = 0; i < kNx; ++i) x[static_cast<std::size_t>(site(i, y, z))] = kD * Vec3(i, y, z) + Vec3(jitter(rng), jitter(rng), jitter(rng));
  for (Index lattice : order) {
    const auto k = static_cast<std::size_t>(lattice);
    s.particles.add(x[k], 0.5 * kD, 2500.0);
    s.particles.id.back() = lattice;
    const int i = lattice % kNx;
    if (i < 2 || i >= kNx - 2) {
      s.particles.flags.back() = kPrescribed;
      s.particles.velocity.back() = Vec3(i < 2 ? kSpeed : -kSpeed, 0, 0);
    }
  }
  for (int z = 0; z < kNz; ++z)
    for (int y = 0; y < kNy; ++y)
      for (int i = 0; i < kNx; ++i) {
        const Index a = slot[static_cast<std::size_t>(site(i, y, z))];
        if (i + 1 < kNx) s.bonds.emplace_back(a, slot[static_cast<std::size_t>(site(i + 1, y, z))]);
        if (y + 1 < kNy) s.bonds.emplace_back(a, slot[static_cast<std::size_t>(site(i, y + 1, z))]);
        if (z + 1 < kNz) s.bonds.emplace_back(a, slot[static_cast<std::size_t>(site(i, y, z + 1))]);
      }
  s.contact = models().contact.get();
  s.bond = models().bond.get();
  return s;
}

std::vector<Index> identity_order() {
  std::vector<Index> o(static_cast<std::size_t>(kNx * kNy * kNz));
  std::iota(o.begin(), o.end(), 0);
  return o;
}

// Final positions and angular velocities indexed by stable id, plus counters.
struct Outcome {
  std::vector<Vec3> position, omega;
  std::size_t contacts = 0, bonds = 0;
  std::int64_t rebuilds = 0;
  double max_displacement = 0;
  double bond_energy = 0;           // Simulation::energies()
  double recorded_bond_energy = 0;  // sum of bonds().energy, when the run records the loads
};

Outcome run(const std::vector<Index>& order, int threads, bool record_bond_loads = false) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  SimulationSetup setup = block(order);
  setup.record_bond_loads = record_bond_loads;
  std::vector<Vec3> start(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) start[static_cast<std::size_t>(setup.particles.id[k])] = setup.particles.position[k];
  Simulation sim(std::move(setup));
  sim.run(kSteps);
  omp_set_num_threads(before);
  Outcome o;
  const Particles& p = sim.particles();
  o.position.resize(p.size());
  o.omega.resize(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto id = static_cast<std::size_t>(p.id[k]);
    o.position[id] = p.position[k];
    o.omega[id] = p.omega[k];
    o.max_displacement = std::max(o.max_displacement, (p.position[k] - start[id]).norm());
  }
  o.contacts = sim.contact_count();
  o.bonds = sim.bonds().size();
  o.rebuilds = sim.neighbour_rebuilds();
  o.bond_energy = sim.energies().bond;
  for (double e : sim.bonds().energy) o.recorded_bond_energy += e;
  return o;
}

// Largest position difference over the largest displacement of the run.
double relative_difference(const Outcome& a, const Outcome& b) {
  double worst = 0;
  for (std::size_t k = 0; k < a.position.size(); ++k) worst = std::max(worst, (a.position[k] - b.position[k]).norm());
  return worst / a.max_displacement;
}

}  // namespace

TEST_CASE("parallel step: the squeezed block exercises contacts, rebuilds and renumbering") {
  const Outcome a = run(identity_order(), 1);
  // Slabs moved 250 steps x dt x 0.2 m/s; contacts formed where bonded neighbours were pressed.
  CHECK(a.contacts > 100);
  CHECK(a.rebuilds >= 2);
  CHECK(a.bonds == static_cast<std::size_t>((kNx - 1) * kNy * kNz + kNx * (kNy - 1) * kNz + kNx * kNy * (kNz - 1)));
}

TEST_CASE("parallel step: two threads give bit-identical runs") {
  const Outcome a = run(identity_order(), 2);
  const Outcome b = run(identity_order(), 2);
  bool identical = a.contacts == b.contacts;
  for (std::size_t k = 0; k < a.position.size(); ++k)
    identical = identical && a.position[k] == b.position[k] && a.omega[k] == b.omega[k];
  CHECK(identical);
}

TEST_CASE("parallel step: one and two threads agree to round-off") {
  // The threads only change the order of the force sums (round-off 1e-16 relative per sum); the
  // squeezed elastic block does not amplify it much in 250 steps, so 1e-9 of the largest
  // displacement separates round-off from any real difference (a lost force is O(1)).
  const Outcome one = run(identity_order(), 1);
  const Outcome two = run(identity_order(), 2);
  CHECK(one.contacts == two.contacts);
  MESSAGE("1 vs 2 threads, max |dx| / max displacement = " << relative_difference(one, two));
  CHECK(relative_difference(one, two) < 1e-9);
}

TEST_CASE("parallel step: the listing order of the particles does not change the physics") {
  // Shuffled input: the kernel renumbers along the Morton curve at construction and at every
  // rebuild, remapping bonds, bond state and contact history. Only summation order may differ.
  std::vector<Index> shuffled = identity_order();
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937_64(3));
  const Outcome plain = run(identity_order(), 1);
  const Outcome mixed = run(shuffled, 1);
  CHECK(plain.contacts == mixed.contacts);
  CHECK(plain.rebuilds == mixed.rebuilds);
  MESSAGE("shuffled vs lattice order, max |dx| / max displacement = " << relative_difference(plain, mixed));
  CHECK(relative_difference(plain, mixed) < 1e-9);
}

TEST_CASE("parallel step: recording every bond's loads changes no bit of the run") {
  // The loads normally live only in a per-thread block buffer; recorded, they are also written to
  // bonds() and carried through renumbering. The step must not notice either way.
  const Outcome plain = run(identity_order(), 2);
  const Outcome recorded = run(identity_order(), 2, true);
  bool identical = plain.contacts == recorded.contacts && plain.bond_energy == recorded.bond_energy;
  for (std::size_t k = 0; k < plain.position.size(); ++k)
    identical = identical && plain.position[k] == recorded.position[k] && plain.omega[k] == recorded.omega[k];
  CHECK(identical);
  CHECK(plain.recorded_bond_energy == 0.0);  // nothing recorded
  REQUIRE(recorded.bond_energy > 0);
  // The same energies summed in another grouping: round-off only (1e-16 per term, ~6e4 terms).
  CHECK(recorded.recorded_bond_energy == doctest::Approx(recorded.bond_energy).epsilon(1e-11).scale(0));
}
