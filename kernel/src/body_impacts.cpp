#include "shard/body_impacts.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "shard/wall.hpp"

namespace shard {
namespace {
constexpr std::size_t kValues = 10;  // per body in a checkpoint: hit, step, time, velocity, normal, wall
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

}  // namespace shard
