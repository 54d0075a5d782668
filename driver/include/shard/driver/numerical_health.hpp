#pragma once
// Watches a running simulation for the signs of a numerical blow-up and stops it within a few
// steps with the step, the particles involved and the likely cause:
//  - a non-finite position, velocity, angular velocity, force or torque;
//  - a particle moving more than half its radius (or turning more than half a radian) in one
//    step: contacts can no longer be resolved, whatever the physics;
//  - mechanical energy gained that no wall put in: kinetic + bond + contact + gravitational
//    energy may only grow by the work of the moving walls (damping and breakage remove energy),
//    so a gain larger than everything seen so far is the exponential growth of an unstable
//    integration, not physics.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/simulation.hpp"

namespace shard {

class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class NumericalHealth {
 public:
  // A particle moving this fraction of its radius, or turning this angle, in one step has left the
  // regime where a contact can be resolved: an overlap can jump from zero to a radius in two steps.
  static constexpr double kMaxStepOverRadius = 0.5;
  static constexpr double kMaxTurnPerStep = 0.5;  // rad

  // The energy scale a gain is judged against at the start: the larger of |energy0| and the
  // round-off floor. A body at rest holds only round-off energy (1e-30 J), whose growth is no
  // blow-up; the kinetic energy of every particle moving 1e-6 of its radius per step is negligible
  // physics, and a real instability passes it within a few steps.
  static double initial_scale(const Simulation& reference, double energy0);

  // `reference` is the state the run started from (the initial packing, or a restart's checkpoint).
  explicit NumericalHealth(const Simulation& reference);

  // Accumulates the work of the moving walls; call after every step.
  void after_step(const Simulation& sim);
  // Throws NumericalError describing the blow-up; `last_good` says where the last good state is.
  void check(const Simulation& sim, const std::string& last_good);

  // For checkpoints: the energy baseline and the walls' work, so a restart checks the same way.
  std::vector<double> state() const;
  void restore(const std::vector<double>& s);

 private:
  std::string likely_cause(const Simulation& sim, const std::vector<Index>& rows) const;

  std::vector<Vec3> initial_position_;
  std::vector<double> initial_radius_;
  std::vector<Index> initial_id_;
  double energy0_ = 0;     // kinetic + bond + contact at the start, J
  double potential0_ = 0;  // gravitational, J
  double wall_work_ = 0;   // done on the particles by the moving walls, J
  double scale_ = 0;       // largest energy magnitude seen at a check, J
};

}  // namespace shard
