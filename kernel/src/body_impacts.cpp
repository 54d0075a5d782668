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
}  // namespace

double BodyImpact::angle_degrees() const {
  const double v = velocity.norm();
  if (v == 0) return 0;
  const double c = std::clamp(velocity.dot(-normal) / v, -1.0, 1.0);
  return std::acos(c) * 180.0 / std::numbers::pi;
}

BodyImpactRecorder::BodyImpactRecorder(const Particles& particles) {
  std::int32_t top = -1;
  for (std::int32_t b : particles.body) top = std::max(top, b);
  const auto bodies = static_cast<std::size_t>(top + 1);
  impacts_.resize(bodies);
  remaining_ = bodies;
  momentum_.resize(bodies);
  centre_.resize(bodies);
  mass_.resize(bodies);
  reach_.resize(bodies);
  near_.resize(bodies);
}

void BodyImpactRecorder::update(const Simulation& simulation) {
  const Particles& p = simulation.particles();
  // Nothing left to record, or particles without body ids (all bodies are then unknown).
  if (remaining_ == 0 || p.body.size() != p.size()) return;
  const std::vector<Wall>& walls = simulation.walls();
  std::fill(momentum_.begin(), momentum_.end(), Vec3::Zero());
  std::fill(centre_.begin(), centre_.end(), Vec3::Zero());
  std::fill(mass_.begin(), mass_.end(), 0.0);
  std::fill(reach_.begin(), reach_.end(), 0.0);
  const std::size_t n = p.size();
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = static_cast<std::size_t>(p.body[k]);
    if (impacts_[b].hit) continue;
    momentum_[b] += p.mass[k] * p.velocity[k];
    centre_[b] += p.mass[k] * p.position[k];
    mass_[b] += p.mass[k];
  }
  for (std::size_t b = 0; b < impacts_.size(); ++b)
    if (!impacts_[b].hit && mass_[b] > 0) centre_[b] /= mass_[b];
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = static_cast<std::size_t>(p.body[k]);
    if (!impacts_[b].hit) reach_[b] = std::max(reach_[b], (p.position[k] - centre_[b]).norm() + p.radius[k]);
  }
  for (std::size_t w = 0; w < walls.size() && remaining_ > 0; ++w) {
    const Wall& wall = walls[w];
    bool any_near = false;
    for (std::size_t b = 0; b < impacts_.size(); ++b) {
      // A plane or mesh that the bounding sphere does not reach cannot touch a sphere of the body;
      // a cylinder's finite length can hide a reachable end from the centre, so it is always tested.
      Vec3 normal;
      double distance = 0;
      near_[b] = !impacts_[b].hit && mass_[b] > 0 &&
                 (wall.shape == WallShape::Cylinder || wall_contact(wall, centre_[b], reach_[b], normal, distance));
      any_near = any_near || near_[b];
    }
    if (!any_near) continue;
    for (std::size_t k = 0; k < n; ++k) {
      const auto b = static_cast<std::size_t>(p.body[k]);
      if (!near_[b] || impacts_[b].hit) continue;
      Vec3 normal;
      double distance = 0;
      // The kernel's own contact condition (simulation.cpp): within reach and closer than the radius.
      if (!wall_contact(wall, p.position[k], p.radius[k], normal, distance) || distance >= p.radius[k]) continue;
      BodyImpact& hit = impacts_[b];
      hit.hit = true;
      hit.step = simulation.step_count();
      hit.time = simulation.time();
      hit.velocity = momentum_[b] / mass_[b];
      hit.normal = normal;
      hit.wall = static_cast<std::int32_t>(w);
      --remaining_;
    }
  }
}

std::vector<double> BodyImpactRecorder::state() const {
  std::vector<double> out;
  out.reserve(kValues * impacts_.size());
  for (const BodyImpact& i : impacts_) {
    out.insert(out.end(), {i.hit ? 1.0 : 0.0, static_cast<double>(i.step), i.time, i.velocity.x(), i.velocity.y(),
                           i.velocity.z(), i.normal.x(), i.normal.y(), i.normal.z(), static_cast<double>(i.wall)});
  }
  return out;
}

void BodyImpactRecorder::restore(const std::vector<double>& state) {
  if (state.size() != kValues * impacts_.size())
    throw std::invalid_argument("the checkpoint's body impacts do not match the scene's bodies");
  remaining_ = impacts_.size();
  for (std::size_t b = 0; b < impacts_.size(); ++b) {
    const double* s = state.data() + kValues * b;
    BodyImpact& i = impacts_[b];
    i.hit = s[0] != 0;
    i.step = static_cast<std::int64_t>(s[1]);
    i.time = s[2];
    i.velocity = Vec3(s[3], s[4], s[5]);
    i.normal = Vec3(s[6], s[7], s[8]);
    i.wall = static_cast<std::int32_t>(s[9]);
    if (i.hit) --remaining_;
  }
}

}  // namespace shard
