#pragma once
// The numerical-health watch of a decomposed run: NumericalHealth's tests (a non-finite or
// too-fast particle, mechanical energy gained that no wall or grip put in) over every rank's own
// particles, reduced in rank order, so every rank throws the same NumericalError at the same step.
// Its state() is NumericalHealth's, so checkpoints restart in either build.
#include <string>
#include <vector>

#include "shard/mpi/distributed_simulation.hpp"

namespace shard::driver {

class DistributedHealth {
 public:
  // `whole` is the whole scene as instantiated (the same on every rank): the energy baseline;
  // `gravity` the scene's, m/s^2.
  DistributedHealth(const Simulation& whole, const Vec3& gravity);
  // Accumulates the work of the walls (rank 0) and of this rank's gripped particles.
  void after_step(const mpi::DistributedSimulation& sim);
  // Collective. Throws NumericalError on every rank alike.
  void check(const mpi::DistributedSimulation& sim, const std::string& last_good);
  // Collective (the work is summed over the ranks).
  std::vector<double> state(const mpi::DistributedSimulation& sim) const;
  void restore(const std::vector<double>& s, int rank);

 private:
  Vec3 gravity_;
  double energy0_ = 0, potential0_ = 0;
  double work_ = 0;  // this rank's share of the work done on the particles by walls and grips, J
  double scale_ = 0;
};

}  // namespace shard::driver
