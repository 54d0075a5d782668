#include "health_watch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace shard::driver::detail {
namespace {

constexpr double kMaxStepOverRadius = NumericalHealth::kMaxStepOverRadius;
constexpr double kMaxTurnPerStep = NumericalHealth::kMaxTurnPerStep;
constexpr std::size_t kNamed = 5;  // particles named in a message

// A particle past a limit and how far (the larger, the worse).
struct Flagged {
  double score = 0;
  Index id = 0;
};

// The worst kNamed, worst first; ties by id, so every decomposition names the same particles.
std::vector<Flagged> worst_first(std::vector<Flagged> v) {
  std::sort(v.begin(), v.end(), [](const Flagged& a, const Flagged& b) {
    return a.score != b.score ? a.score > b.score : a.id < b.id;
  });
  if (v.size() > kNamed) v.resize(kNamed);
  return v;
}

// The ids of the worst kNamed over every rank's own.
std::vector<Index> worst_over_ranks(const RunBackend& run, const std::vector<Flagged>& mine) {
  std::vector<double> flat;
  for (const Flagged& f : worst_first(mine)) flat.insert(flat.end(), {f.score, static_cast<double>(f.id)});
  const std::vector<double> all = run.gather_over_ranks(flat);
  std::vector<Flagged> merged;
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) merged.push_back({all[k], static_cast<Index>(all[k + 1])});
  std::vector<Index> ids;
  for (const Flagged& f : worst_first(std::move(merged))) ids.push_back(f.id);
  return ids;
}

std::string ids_text(const std::vector<Index>& ids, double count) {
  std::string out;
  for (std::size_t k = 0; k < ids.size(); ++k) out += fmt::format("{}{}", k ? ", " : "", ids[k]);
  const double more = count - static_cast<double>(ids.size());
  if (more > 0) out += fmt::format(" and {:.0f} more", more);
  return out;
}

Index stable_id(const Particles& p, std::size_t k) { return p.id.size() == p.size() ? p.id[k] : static_cast<Index>(k); }

// This rank's own particles: the non-finite and the too fast ones, and the energy of the others.
struct OwnScan {
  std::vector<Flagged> non_finite, fast;
  double kinetic = 0, gravity = 0;
};

OwnScan scan(const RunBackend& run, const Vec3& gravity) {
  const Particles& p = run.local().particles();
  const double dt = run.local().dt();
  const auto finite = [](const Vec3& v) { return v.allFinite(); };
  OwnScan out;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!run.owns(k)) continue;
    if (!finite(p.position[k]) || !finite(p.velocity[k]) || !finite(p.omega[k]) || !finite(p.force[k]) ||
        !finite(p.torque[k])) {
      out.non_finite.push_back({1.0, stable_id(p, k)});
      continue;
    }
    const double ratio = std::max(p.velocity[k].norm() * dt / (kMaxStepOverRadius * p.radius[k]),
                                  p.omega[k].norm() * dt / kMaxTurnPerStep);
    if (ratio > 1) out.fast.push_back({ratio, stable_id(p, k)});
    out.kinetic += 0.5 * p.mass[k] * p.velocity[k].squaredNorm() + 0.5 * p.inertia[k] * p.omega[k].squaredNorm();
    out.gravity -= p.mass[k] * gravity.dot(p.position[k]);
  }
  return out;
}

// This rank's own moving particles by kinetic energy (twice it), for a message naming the fastest.
std::vector<Flagged> moving(const RunBackend& run) {
  const Particles& p = run.local().particles();
  std::vector<Flagged> out;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double e = p.mass[k] * p.velocity[k].squaredNorm() + p.inertia[k] * p.omega[k].squaredNorm();
    if (run.owns(k) && e > 0) out.push_back({e, stable_id(p, k)});
  }
  return out;
}

}  // namespace

NumericalHealth::NumericalHealth(const WholeScene& whole, const Simulation* packing, const Vec3& gravity,
                                 RunDamping damping)
    : gravity_(gravity),
      limits_(whole.limits),
      damping_(std::move(damping)),
      energy0_(whole.energy0),
      potential0_(whole.potential0),
      scale_(whole.energy_scale) {
  if (!packing) return;
  initial_position_ = packing->particles().position;
  initial_radius_ = packing->particles().radius;
  initial_id_ = packing->particles().id;
}

void NumericalHealth::after_step(const RunBackend& run) {
  const Simulation& local = run.local();
  // The walls' loads are the run's on every rank: rank 0 counts their work.
  if (run.rank() == 0)
    for (const Wall& w : local.walls()) work_ -= w.force.dot(w.velocity) * local.dt();
  // Gripped particles (held velocity) are driven too: their grip supplies the opposite of the
  // force the body exerts on them, and that work enters the body.
  const Particles& p = local.particles();
  for (std::size_t k = 0; k < p.size(); ++k)
    if ((p.flags[k] & kPrescribed) && run.owns(k))
      work_ -= (p.force[k].dot(p.velocity[k]) + p.torque[k].dot(p.omega[k])) * local.dt();
}

void NumericalHealth::check(const RunBackend& run, const std::string& last_good) {
  const Simulation& local = run.local();
  const double dt = local.dt();
  const OwnScan own = scan(run, gravity_);
  const Energies mine = local.energies();  // bonds and contacts: this rank's own
  const std::vector<double> all = run.sum_over_ranks({own.kinetic, own.gravity, mine.bond, mine.contact, work_,
                                                      static_cast<double>(own.non_finite.size()),
                                                      static_cast<double>(own.fast.size())});
  const std::string when = fmt::format("step {} (t = {:.6g} s)", local.step_count(), local.time());
  const auto fail = [&](const std::string& what, const std::vector<Index>& ids, double count) {
    throw NumericalError(fmt::format("{}: the run blew up: {} (particle ids {}). Likely cause: {}. {}", when, what,
                                     ids_text(ids, count), likely_cause(run, dt, ids), last_good));
  };
  if (all[5] > 0) fail("non-finite position, velocity or force", worst_over_ranks(run, own.non_finite), all[5]);
  if (all[6] > 0)
    fail(fmt::format("particles move more than {} of their radius (or {} rad) in one step of {:.4g} s",
                     kMaxStepOverRadius, kMaxTurnPerStep, dt),
         worst_over_ranks(run, own.fast), all[6]);
  const double mechanical = all[0] + all[2] + all[3];
  const double potential = all[1] - potential0_;
  const double work = all[4];
  const double gain = mechanical + potential - energy0_ - work;
  if (!std::isfinite(gain)) fail("non-finite energy", {}, 0);
  // Both: larger than every energy seen before, and most of what the particles now hold (so the
  // round-off of a run that starts at rest, where everything seen so far is ~0, never counts).
  if (gain > scale_ && gain > 0.5 * mechanical) {
    const std::vector<Flagged> fastest = moving(run);
    fail(fmt::format("the mechanical energy grew by {:.4g} J without work from the walls or grips (largest energy so "
                     "far {:.4g} J): the integration is unstable",
                     gain, scale_),
         worst_over_ranks(run, fastest), run.sum_over_ranks({static_cast<double>(fastest.size())})[0]);
  }
  scale_ = std::max({scale_, std::abs(mechanical), std::abs(potential), std::abs(work), std::abs(energy0_)});
}

// The damping's shortened critical step (damped_stable_step) as a cause, when the step is above it.
std::string NumericalHealth::damped_step_cause(const TimeStepLimit& limit, double dt) const {
  if (!(damping_.fraction > 0)) return "";
  const double damped = damped_stable_step(limit.critical, damping_.fraction);
  if (dt <= damped) return "";
  return fmt::format("Cundall's damping [simulation] {} = {:g} lets a slowing particle's force grow by that fraction, "
                     "which shortens the critical step {:.4g} s of {} to {:.4g} s, below the time step {:.4g} s (a "
                     "regular lattice reaches that limit): set [simulation] dt to at most {:.4g} s, or lower {}",
                     damping_.key, damping_.fraction, limit.critical, limit.name, damped, dt, damped, damping_.key);
}

std::string NumericalHealth::likely_cause(const RunBackend& run, double dt, const std::vector<Index>& ids) const {
  std::vector<std::string> causes;
  for (const auto& limit : limits_) {
    if (dt > limit.critical)
      causes.push_back(fmt::format("the time step {:.4g} s is above the critical step {:.4g} s of {}: set [simulation] "
                                   "dt = \"auto\" or at most {:.4g} s",
                                   dt, limit.critical, limit.name, limit.recommended));
    else if (const std::string damped = damped_step_cause(limit, dt); !damped.empty())
      causes.push_back(damped);
  }
  const std::string overlap = initial_overlap(run, ids);
  if (!overlap.empty()) causes.push_back(overlap);
  if (causes.empty())
    causes.push_back(fmt::format("no model's time-step limit is exceeded (dt = {:.4g} s); look for a wall moving too "
                                 "fast, a stiffness or damping parameter off by orders of magnitude, or halve dt",
                                 dt));
  std::string out;
  for (std::size_t k = 0; k < causes.size(); ++k) out += (k ? "; or " : "") + causes[k];
  return out;
}

// Overlaps of the named particles in the starting state: a packing generated or edited with
// spheres inside one another releases their overlap energy at once. Only the process holding the
// initial packing finds one; the others add zeros to its figures, so every rank words it alike.
std::string NumericalHealth::initial_overlap(const RunBackend& run, const std::vector<Index>& ids) const {
  double deepest = 0;
  Index a_id = 0, b_id = 0;
  for (const Index id : ids) {
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
  const std::vector<double> found =
      run.sum_over_ranks({deepest, static_cast<double>(a_id), static_cast<double>(b_id)});
  deepest = found[0];
  a_id = static_cast<Index>(found[1]);
  b_id = static_cast<Index>(found[2]);
  if (deepest <= 0.1) return {};
  return fmt::format("an overlapping initial packing: particles {} and {} overlapped by {:.0f} % of the smaller radius "
                     "at the start; regenerate the packing with a gap or check the particle file",
                     a_id, b_id, 100 * deepest);
}

std::vector<double> NumericalHealth::state(const RunBackend& run) const {
  return {energy0_, potential0_, run.sum_over_ranks({work_})[0], scale_};
}

void NumericalHealth::restore(const std::vector<double>& s, int rank) {
  if (s.size() != 4) throw std::invalid_argument("the checkpoint's energy record has the wrong length");
  energy0_ = s[0];
  potential0_ = s[1];
  work_ = rank == 0 ? s[2] : 0.0;  // the past work once, on rank 0
  scale_ = s[3];
}

}  // namespace shard::driver::detail
