#pragma once
// Watches a running simulation, serial or decomposed (run_backend.hpp), for the signs of a
// numerical blow-up and stops it within a few steps with the step, the particles involved and the
// likely cause:
//  - a non-finite position, velocity, angular velocity, force or torque;
//  - a particle moving more than half its radius (or turning more than half a radian) in one
//    step: contacts can no longer be resolved, whatever the physics;
//  - mechanical energy gained that no wall put in: kinetic + bond + contact + gravitational
//    energy may only grow by the work of the moving walls (damping and breakage remove energy),
//    so a gain larger than everything seen so far is the exponential growth of an unstable
//    integration, not physics.
// Each rank looks at its own particles; the counts, energies and worst particles are reduced in
// rank order, so every rank throws the same NumericalError at the same step.
#include <cmath>
#include <string>
#include <vector>

#include "run_backend.hpp"
#include "whole_scene.hpp"
#include "shard/driver/numerical_health.hpp"

namespace shard::driver::detail {

// The Cundall damping fraction that limits a run's stable step and the [simulation] key that sets
// it: the damping shortens the models' critical time steps (NumericalHealth::likely_cause).
struct RunDamping {
  double fraction = 0;
  std::string key;
};

// Cundall's damping takes alpha |F| off a particle's force while it speeds up and adds it while it
// slows down: on the way back an oscillator's spring acts (1 + alpha) times as stiff, and velocity
// Verlet, stable up to omega dt = 2, is stable only up to `step` / sqrt(1 + alpha). A regular
// lattice, whose stiffest mode reaches the bond's critical step, gains energy at rest beyond it.
inline double damped_stable_step(double step, double damping) { return step / std::sqrt(1 + damping); }

class NumericalHealth {
 public:
  // A particle moving this fraction of its radius, or turning this angle, in one step has left the
  // regime where a contact can be resolved: an overlap can jump from zero to a radius in two steps.
  static constexpr double kMaxStepOverRadius = 0.5;
  static constexpr double kMaxTurnPerStep = 0.5;  // rad

  // `whole`: the whole scene's energy baseline and time-step limits (the same on every rank);
  // `packing`: the whole scene's Simulation at the start where this process holds it (null
  // elsewhere), the initial packing a message looks into; `gravity` the scene's, m/s^2; `damping`
  // the Cundall damping that limits the run's stable step.
  NumericalHealth(const WholeScene& whole, const Simulation* packing, const Vec3& gravity, RunDamping damping);

  // Accumulates the work of the walls (rank 0) and of this rank's gripped particles; call after
  // every step.
  void after_step(const RunBackend& run);
  // Collective. Throws NumericalError describing the blow-up; `last_good` says where the last good
  // state is.
  void check(const RunBackend& run, const std::string& last_good);

  // For checkpoints: the energy baseline and the walls' work, so a restart checks the same way.
  // state() is collective (the work is summed over the ranks); restore gives the past work to
  // rank 0 alone.
  std::vector<double> state(const RunBackend& run) const;
  void restore(const std::vector<double>& s, int rank);

 private:
  // Collective (the initial packing is on one rank).
  std::string likely_cause(const RunBackend& run, double dt, const std::vector<Index>& ids) const;
  std::string initial_overlap(const RunBackend& run, const std::vector<Index>& ids) const;
  // The time step `dt` lies below `limit`'s critical step but above the one the damping leaves.
  std::string damped_step_cause(const TimeStepLimit& limit, double dt) const;

  Vec3 gravity_;
  std::vector<TimeStepLimit> limits_;
  RunDamping damping_;
  std::vector<Vec3> initial_position_;  // empty where the whole scene was not instantiated
  std::vector<double> initial_radius_;
  std::vector<Index> initial_id_;
  double energy0_ = 0;     // kinetic + bond + contact at the start, J
  double potential0_ = 0;  // gravitational, J
  double work_ = 0;        // this rank's share of the work done on the particles by walls and grips, J
  double scale_ = 0;       // largest energy magnitude seen at a check, J
};

}  // namespace shard::driver::detail
