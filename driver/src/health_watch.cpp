#include "distributed_health.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shard/driver/numerical_health.hpp"

namespace shard::driver {
namespace {

constexpr double kMaxStepOverRadius = NumericalHealth::kMaxStepOverRadius;
constexpr double kMaxTurnPerStep = NumericalHealth::kMaxTurnPerStep;

}  // namespace

DistributedHealth::DistributedHealth(const Simulation& whole, const Vec3& gravity) : gravity_(gravity) {
  const Energies e = whole.energies();
  energy0_ = e.kinetic + e.bond + e.contact;
  potential0_ = e.gravity;
  scale_ = NumericalHealth::initial_scale(whole, energy0_);
}

void DistributedHealth::after_step(const mpi::DistributedSimulation& sim) {
  const Simulation& local = sim.local();
  // The walls' loads are the run's on every rank: rank 0 counts their work.
  if (sim.rank() == 0)
    for (const Wall& w : local.walls()) work_ -= w.force.dot(w.velocity) * local.dt();
  const Particles& p = local.particles();
  for (std::size_t k = 0; k < p.size(); ++k)
    if ((p.flags[k] & kPrescribed) && sim.owns(k))
      work_ -= (p.force[k].dot(p.velocity[k]) + p.torque[k].dot(p.omega[k])) * local.dt();
}

void DistributedHealth::check(const mpi::DistributedSimulation& sim, const std::string& last_good) {
  const Simulation& local = sim.local();
  const Particles& p = local.particles();
  const double dt = local.dt();
  const auto finite = [](const Vec3& v) { return v.allFinite(); };
  double kinetic = 0, gravity = 0, non_finite = 0, fast = 0;
  double worst_id = -1, worst = 0;  // the particle of this rank furthest past a limit
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!sim.owns(k)) continue;
    if (!finite(p.position[k]) || !finite(p.velocity[k]) || !finite(p.omega[k]) || !finite(p.force[k]) ||
        !finite(p.torque[k])) {
      if (non_finite++ == 0) worst_id = p.id[k];  // a non-finite particle outranks any fast one
      worst = INFINITY;
      continue;
    }
    const double ratio = std::max(p.velocity[k].norm() * dt / (kMaxStepOverRadius * p.radius[k]),
                                  p.omega[k].norm() * dt / kMaxTurnPerStep);
    if (ratio > 1) ++fast;
    if (ratio > 1 && ratio > worst) {
      worst = ratio;
      worst_id = p.id[k];
    }
    kinetic += 0.5 * p.mass[k] * p.velocity[k].squaredNorm() + 0.5 * p.inertia[k] * p.omega[k].squaredNorm();
    gravity -= p.mass[k] * gravity_.dot(p.position[k]);
  }
  const Energies own = local.energies();  // bonds and contacts: this rank's own
  std::vector<double> mine{kinetic, gravity, own.bond, own.contact, work_, non_finite, fast};
  mine.resize(7 + static_cast<std::size_t>(sim.ranks()), 0.0);
  mine[7 + static_cast<std::size_t>(sim.rank())] = worst_id;
  const std::vector<double> all = sim.sum_over_ranks(mine);
  std::string ids;
  for (int r = 0; r < sim.ranks(); ++r)
    if (all[7 + static_cast<std::size_t>(r)] >= 0)
      ids += fmt::format("{}{} (rank {})", ids.empty() ? "" : ", ", all[7 + static_cast<std::size_t>(r)], r);
  const std::string when = fmt::format("step {} (t = {:.6g} s)", local.step_count(), local.time());
  const auto fail = [&](const std::string& what) {
    throw NumericalError(fmt::format("{}: the run blew up: {} (particle ids {}). Likely cause: the time step or the "
                                     "stiffness (compare dt with the time step limits at the start of the run). {}",
                                     when, what, ids.empty() ? "-" : ids, last_good));
  };
  if (all[5] > 0) fail(fmt::format("{:.0f} particles with a non-finite position, velocity or force", all[5]));
  if (all[6] > 0)
    fail(fmt::format("{:.0f} particles move more than {} of their radius (or {} rad) in one step of {:.4g} s", all[6],
                     kMaxStepOverRadius, kMaxTurnPerStep, dt));
  const double mechanical = all[0] + all[2] + all[3];
  const double potential = all[1] - potential0_;
  const double work = all[4];
  const double gain = mechanical + potential - energy0_ - work;
  if (!std::isfinite(gain)) fail("non-finite energy");
  if (gain > scale_ && gain > 0.5 * mechanical)
    fail(fmt::format("the mechanical energy grew by {:.4g} J without work from the walls or grips (largest energy so "
                     "far {:.4g} J): the integration is unstable",
                     gain, scale_));
  scale_ = std::max({scale_, std::abs(mechanical), std::abs(potential), std::abs(work), std::abs(energy0_)});
}

std::vector<double> DistributedHealth::state(const mpi::DistributedSimulation& sim) const {
  return {energy0_, potential0_, sim.sum_over_ranks({work_})[0], scale_};
}

void DistributedHealth::restore(const std::vector<double>& s, int rank) {
  if (s.size() != 4) throw std::invalid_argument("the checkpoint's energy record has the wrong length");
  energy0_ = s[0];
  potential0_ = s[1];
  work_ = rank == 0 ? s[2] : 0.0;  // the past work once, on rank 0
  scale_ = s[3];
}

}  // namespace shard::driver
