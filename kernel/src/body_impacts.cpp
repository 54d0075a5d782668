#include "shard/body_impacts.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "shard/simulation.hpp"
#include "shard/wall.hpp"

namespace shard {
namespace {
constexpr std::size_t kValues = 10;  // per body in a checkpoint: hit, step, time, velocity, normal, wall

// The sphere's stable id; its index when the particles carry none (a state from before ids).
Index stable_id(const Particles& p, std::size_t k) { return p.id.size() == p.size() ? p.id[k] : static_cast<Index>(k); }
}  // namespace

std::vector<double> impacts_state(const std::vector<BodyImpact>& impacts) {
  std::vector<double> out;
  out.reserve(kValues * impacts.size());
  for (const BodyImpact& i : impacts) {
    out.insert(out.end(), {i.hit ? 1.0 : 0.0, static_cast<double>(i.step), i.time, i.velocity.x(), i.velocity.y(),
                           i.velocity.z(), i.normal.x(), i.normal.y(), i.normal.z(), static_cast<double>(i.wall)});
  }
  return out;
}

std::vector<BodyImpact> impacts_from_state(const std::vector<double>& state, std::size_t bodies) {
  if (state.size() != kValues * bodies)
    throw std::invalid_argument("the checkpoint's body impacts do not match the scene's bodies");
  std::vector<BodyImpact> impacts(bodies);
  for (std::size_t b = 0; b < bodies; ++b) {
    const double* s = state.data() + kValues * b;
    BodyImpact& i = impacts[b];
    i.hit = s[0] != 0;
    i.step = static_cast<std::int64_t>(s[1]);
    i.time = s[2];
    i.velocity = Vec3(s[3], s[4], s[5]);
    i.normal = Vec3(s[6], s[7], s[8]);
    i.wall = static_cast<std::int32_t>(s[9]);
  }
  return impacts;
}

double BodyImpact::angle_degrees() const {
  const double v = velocity.norm();
  if (v == 0) return 0;
  const double c = std::clamp(velocity.dot(-normal) / v, -1.0, 1.0);
  return std::acos(c) * 180.0 / std::numbers::pi;
}

bool carries_bodies(const Wall& wall) { return !wall.surface_velocity.isZero(); }

BodyImpactRecorder::BodyImpactRecorder(const Particles& particles) {
  std::int32_t top = -1;
  for (std::int32_t b : particles.body) top = std::max(top, b);
  const auto bodies = static_cast<std::size_t>(top + 1);
  impacts_.resize(bodies);
  remaining_ = bodies;
  candidate_.resize(bodies);
  pending_.reserve(bodies);
  momentum_.resize(bodies);
  centre_.resize(bodies);
  mass_.resize(bodies);
  reach_.resize(bodies);
  near_.resize(bodies);
}

void BodyImpactRecorder::offer(std::size_t body, std::int32_t wall, Index particle, const Vec3& normal) {
  if (impacts_[body].hit) return;
  Candidate& c = candidate_[body];
  if (c.wall < 0) {
    pending_.push_back(body);
  } else if (wall > c.wall || (wall == c.wall && particle > c.particle)) {
    return;
  }
  c = {wall, particle, normal};
}

void BodyImpactRecorder::update(const Simulation& simulation) {
  const Particles& p = simulation.particles();
  const std::int64_t step = simulation.step_count();
  const bool follows = last_step_ >= 0 && step == last_step_ + 1;
  last_step_ = step;
  // Nothing left to record, or particles without body ids (all bodies are then unknown).
  if (remaining_ == 0 || p.body.size() != p.size()) return;
  if (!follows) {
    scan(simulation);
  } else {
    // A body without an impact touched no wall but its carriers at the last step (else it would
    // have one), so every contact it has now with another wall began in this step.
    const std::vector<Wall>& walls = simulation.walls();
    for (const WallContactStart& c : simulation.wall_contacts_begun()) {
      if (carries_bodies(walls[static_cast<std::size_t>(c.wall)])) continue;
      const auto k = static_cast<std::size_t>(c.particle);
      offer(static_cast<std::size_t>(p.body[k]), c.wall, stable_id(p, k), c.normal);
    }
  }
  if (!pending_.empty()) record(simulation);
}

// Every sphere of every body without an impact against every wall that does not carry it, with the
// kernel's own contact condition (simulation.cpp): within reach and closer than the radius. A
// sphere is tested only while its body's bounding sphere reaches the wall (a cylinder is always
// tested: its finite length can hide a reachable end from the centre).
void BodyImpactRecorder::scan(const Simulation& simulation) {
  const Particles& p = simulation.particles();
  const std::vector<Wall>& walls = simulation.walls();
  const std::size_t n = p.size();
  std::fill(centre_.begin(), centre_.end(), Vec3::Zero());
  std::fill(mass_.begin(), mass_.end(), 0.0);
  std::fill(reach_.begin(), reach_.end(), 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = static_cast<std::size_t>(p.body[k]);
    if (impacts_[b].hit) continue;
    centre_[b] += p.mass[k] * p.position[k];
    mass_[b] += p.mass[k];
  }
  for (std::size_t b = 0; b < impacts_.size(); ++b)
    if (!impacts_[b].hit && mass_[b] > 0) centre_[b] /= mass_[b];
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = static_cast<std::size_t>(p.body[k]);
    if (!impacts_[b].hit) reach_[b] = std::max(reach_[b], (p.position[k] - centre_[b]).norm() + p.radius[k]);
  }
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const Wall& wall = walls[w];
    if (carries_bodies(wall)) continue;
    bool any_near = false;
    for (std::size_t b = 0; b < impacts_.size(); ++b) {
      Vec3 normal;
      double distance = 0;
      near_[b] = !impacts_[b].hit && mass_[b] > 0 &&
                 (wall.shape == WallShape::Cylinder || wall_contact(wall, centre_[b], reach_[b], normal, distance));
      any_near = any_near || near_[b];
    }
    if (!any_near) continue;
    for (std::size_t k = 0; k < n; ++k) {
      const auto b = static_cast<std::size_t>(p.body[k]);
      if (!near_[b]) continue;
      Vec3 normal;
      double distance = 0;
      if (!wall_contact(wall, p.position[k], p.radius[k], normal, distance) || distance >= p.radius[k]) continue;
      offer(b, static_cast<std::int32_t>(w), stable_id(p, k), normal);
    }
  }
}

// The pending bodies' impacts, with their centre-of-mass velocities summed over their spheres in
// particle order.
void BodyImpactRecorder::record(const Simulation& simulation) {
  const Particles& p = simulation.particles();
  for (std::size_t b : pending_) {
    momentum_[b] = Vec3::Zero();
    mass_[b] = 0;
  }
  const std::size_t n = p.size();
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = static_cast<std::size_t>(p.body[k]);
    if (candidate_[b].wall < 0) continue;
    momentum_[b] += p.mass[k] * p.velocity[k];
    mass_[b] += p.mass[k];
  }
  for (std::size_t b : pending_) {
    Candidate& c = candidate_[b];
    BodyImpact& hit = impacts_[b];
    hit.hit = true;
    hit.step = simulation.step_count();
    hit.time = simulation.time();
    hit.velocity = momentum_[b] / mass_[b];
    hit.normal = c.normal;
    hit.wall = c.wall;
    --remaining_;
    c = Candidate{};
  }
  pending_.clear();
}

std::vector<double> BodyImpactRecorder::state() const { return impacts_state(impacts_); }

void BodyImpactRecorder::restore(const std::vector<double>& state) {
  impacts_ = impacts_from_state(state, impacts_.size());
  remaining_ = static_cast<std::size_t>(std::count_if(impacts_.begin(), impacts_.end(), [](const BodyImpact& i) { return !i.hit; }));
  last_step_ = -1;  // the contacts begun before the restart are not known: the next update scans
}

}  // namespace shard
