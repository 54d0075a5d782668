#pragma once
// The bonded block of the MPI tests (test_mpi_block.cpp, test_mpi_migration.cpp): pulled apart by
// two slabs of prescribed particles while gravity presses it onto a floor wall, so bonds, contacts
// with history, a wall, migration and re-partitions all take part, and bonds break.
#include <algorithm>
#include <random>
#include <vector>

#include "../common/beam_hertz_models.hpp"
#include "shard/simulation.hpp"

namespace shard::testing {

constexpr int kNx = 24, kNy = 10, kNz = 8;
constexpr double kD = 1e-3;     // m, diameter and lattice spacing
constexpr double kSpeed = 1.0;  // m/s, each slab

using Models = BeamHertzModels;

// Lattice of kNx x kNy x kNz spheres (jittered), neighbours along the axes bonded, ids shuffled so
// that id order is not storage order; the two end layers at each x end are pulled apart.
inline SimulationSetup block(const Models& m) {
  const int n = kNx * kNy * kNz;
  std::vector<Index> id(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) id[static_cast<std::size_t>(k)] = k;
  std::shuffle(id.begin(), id.end(), std::mt19937_64(9));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jitter(-0.02 * kD, 0.02 * kD);
  SimulationSetup s;
  const auto site = [](int x, int y, int z) { return static_cast<Index>((z * kNy + y) * kNx + x); };
  for (int z = 0; z < kNz; ++z)
    for (int y = 0; y < kNy; ++y)
      for (int x = 0; x < kNx; ++x) {
        s.particles.add(kD * Vec3(x, y, z) + Vec3(jitter(rng), jitter(rng), jitter(rng)), 0.5 * kD, 2500.0);
        s.particles.id.back() = id[static_cast<std::size_t>(site(x, y, z))];
        if (x < 2 || x >= kNx - 2) {
          s.particles.flags.back() = kPrescribed;
          s.particles.velocity.back() = Vec3(x < 2 ? -kSpeed : kSpeed, 0, 0);
        }
        if (x + 1 < kNx) s.bonds.emplace_back(site(x, y, z), site(x + 1, y, z));
        if (y + 1 < kNy) s.bonds.emplace_back(site(x, y, z), site(x, y + 1, z));
        if (z + 1 < kNz) s.bonds.emplace_back(site(x, y, z), site(x, y, z + 1));
      }
  s.contact = m.contact.get();
  s.bond = m.bond.get();
  s.gravity = Vec3(0, 0, -9.81);
  Wall floor;
  floor.name = "floor";
  floor.axis = Vec3(0, 0, 1);
  floor.point = Vec3(0, 0, -0.49 * kD);  // the bottom layer sits 1e-5 m into it
  s.walls.push_back(floor);
  return s;
}

}  // namespace shard::testing
