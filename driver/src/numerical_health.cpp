#include "shard/driver/numerical_health.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace shard {
namespace {

constexpr double kMaxStepOverRadius = NumericalHealth::kMaxStepOverRadius;
constexpr double kMaxTurnPerStep = NumericalHealth::kMaxTurnPerStep;
constexpr std::size_t kNamed = 5;        // particles named in a message

bool finite(const Vec3& v) { return v.allFinite(); }

std::string ids_text(const Particles& p, const std::vector<Index>& rows) {
  std::string out;
  for (std::size_t k = 0; k < rows.size() && k < kNamed; ++k)
    out += fmt::format("{}{}", k ? ", " : "", p.id[static_cast<std::size_t>(rows[k])]);
  if (rows.size() > kNamed) out += fmt::format(" and {} more", rows.size() - kNamed);
  return out;
}

// Row indices sorted by decreasing score, only those with score > 0 kept.
std::vector<Index> worst(const std::vector<double>& score) {
  std::vector<Index> rows;
  for (std::size_t k = 0; k < score.size(); ++k)
    if (score[k] > 0) rows.push_back(static_cast<Index>(k));
  std::stable_sort(rows.begin(), rows.end(), [&](Index a, Index b) {
    return score[static_cast<std::size_t>(a)] > score[static_cast<std::size_t>(b)];
  });
  return rows;
}

}  // namespace

NumericalHealth::NumericalHealth(const Simulation& reference)
    : initial_position_(reference.particles().position),
      initial_radius_(reference.particles().radius),
      initial_id_(reference.particles().id) {
  const Energies e = reference.energies();
  energy0_ = e.kinetic + e.bond + e.contact;
  potential0_ = e.gravity;
  scale_ = initial_scale(reference, energy0_);
}

double NumericalHealth::initial_scale(const Simulation& reference, double energy0) {
  double round_off_floor = 0;
  const Particles& p = reference.particles();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double v = 1e-6 * p.radius[k] / reference.dt();
    round_off_floor += 0.5 * p.mass[k] * v * v;
  }
  return std::max(std::abs(energy0), round_off_floor);
}

void NumericalHealth::after_step(const Simulation& sim) {
  for (const Wall& w : sim.walls()) wall_work_ -= w.force.dot(w.velocity) * sim.dt();
  // Gripped particles (held velocity) are driven too: their grip supplies the opposite of the
  // force the body exerts on them, and that work enters the body.
  const Particles& p = sim.particles();
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.flags[k] & kPrescribed)
      wall_work_ -= (p.force[k].dot(p.velocity[k]) + p.torque[k].dot(p.omega[k])) * sim.dt();
}

void NumericalHealth::check(const Simulation& sim, const std::string& last_good) {
  const Particles& p = sim.particles();
  const std::size_t n = p.size();
  const double dt = sim.dt();
  std::vector<double> non_finite(n, 0.0), step_ratio(n, 0.0);
  bool any_non_finite = false, any_fast = false;
  for (std::size_t k = 0; k < n; ++k) {
    if (!finite(p.position[k]) || !finite(p.velocity[k]) || !finite(p.omega[k]) || !finite(p.force[k]) ||
        !finite(p.torque[k])) {
      non_finite[k] = 1;
      any_non_finite = true;
      continue;
    }
    const double ratio =
        std::max(p.velocity[k].norm() * dt / (kMaxStepOverRadius * p.radius[k]), p.omega[k].norm() * dt / kMaxTurnPerStep);
    if (ratio > 1) {
      step_ratio[k] = ratio;
      any_fast = true;
    }
  }
  const std::string when = fmt::format("step {} (t = {:.6g} s)", sim.step_count(), sim.time());
  auto fail = [&](const std::string& what, const std::vector<Index>& rows) {
    throw NumericalError(fmt::format("{}: the run blew up: {} (particle ids {}). Likely cause: {}. {}", when, what,
                                     ids_text(p, rows), likely_cause(sim, rows), last_good));
  };
  if (any_non_finite) fail("non-finite position, velocity or force", worst(non_finite));
  if (any_fast)
    fail(fmt::format("particles move more than {} of their radius (or {} rad) in one step of {:.4g} s",
                     kMaxStepOverRadius, kMaxTurnPerStep, dt),
         worst(step_ratio));

  const Energies e = sim.energies();
  const double mechanical = e.kinetic + e.bond + e.contact;
  const double potential = e.gravity - potential0_;
  const double gain = mechanical + potential - energy0_ - wall_work_;
  if (!std::isfinite(gain)) fail("non-finite energy", worst(non_finite));
  // Both: larger than every energy seen before, and most of what the particles now hold (so the
  // round-off of a run that starts at rest, where everything seen so far is ~0, never counts).
  if (gain > scale_ && gain > 0.5 * mechanical) {
    std::vector<double> kinetic(n);
    for (std::size_t k = 0; k < n; ++k)
      kinetic[k] = p.mass[k] * p.velocity[k].squaredNorm() + p.inertia[k] * p.omega[k].squaredNorm();
    fail(fmt::format("the mechanical energy grew by {:.4g} J without work from the walls or grips (largest energy so far "
                     "{:.4g} J): the integration is unstable",
                     gain, scale_),
         worst(kinetic));
  }
  scale_ = std::max({scale_, std::abs(mechanical), std::abs(potential), std::abs(wall_work_), std::abs(energy0_)});
}

std::string NumericalHealth::likely_cause(const Simulation& sim, const std::vector<Index>& rows) const {
  std::vector<std::string> causes;
  for (const auto& limit : sim.time_step_limits())
    if (sim.dt() > limit.critical)
      causes.push_back(fmt::format("the time step {:.4g} s is above the critical step {:.4g} s of {}: set [simulation] "
                                   "dt = \"auto\" or at most {:.4g} s",
                                   sim.dt(), limit.critical, limit.name, limit.recommended));
  // Overlaps of the named particles in the starting state: a packing generated or edited with
  // spheres inside one another releases their overlap energy at once.
  const Particles& p = sim.particles();
  double deepest = 0;
  Index a_id = 0, b_id = 0;
  for (std::size_t k = 0; k < rows.size() && k < kNamed; ++k) {
    const Index id = p.id[static_cast<std::size_t>(rows[k])];
    const auto it = std::find(initial_id_.begin(), initial_id_.end(), id);
    if (it == initial_id_.end()) continue;
    const auto a = static_cast<std::size_t>(it - initial_id_.begin());
    for (std::size_t b = 0; b < initial_position_.size(); ++b) {
      if (b == a) continue;
      const double overlap =
          initial_radius_[a] + initial_radius_[b] - (initial_position_[a] - initial_position_[b]).norm();
      const double relative = overlap / std::min(initial_radius_[a], initial_radius_[b]);
      if (relative > deepest) {
        deepest = relative;
        a_id = id;
        b_id = initial_id_[b];
      }
    }
  }
  if (deepest > 0.1)
    causes.push_back(fmt::format("an overlapping initial packing: particles {} and {} overlapped by {:.0f} % of the "
                                 "smaller radius at the start; regenerate the packing with a gap or check the "
                                 "particle file",
                                 a_id, b_id, 100 * deepest));
  if (causes.empty())
    causes.push_back(fmt::format("no model's time-step limit is exceeded (dt = {:.4g} s); look for a wall moving too "
                                 "fast, a stiffness or damping parameter off by orders of magnitude, or halve dt",
                                 sim.dt()));
  std::string out;
  for (std::size_t k = 0; k < causes.size(); ++k) out += (k ? "; or " : "") + causes[k];
  return out;
}

std::vector<double> NumericalHealth::state() const { return {energy0_, potential0_, wall_work_, scale_}; }

void NumericalHealth::restore(const std::vector<double>& s) {
  if (s.size() != 4) throw std::invalid_argument("the checkpoint's energy record has the wrong length");
  energy0_ = s[0];
  potential0_ = s[1];
  wall_work_ = s[2];
  scale_ = s[3];
}

}  // namespace shard
