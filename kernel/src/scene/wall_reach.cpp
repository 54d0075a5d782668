#include "wall_reach.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace shard::scene_detail {
namespace {

constexpr double kEndless = -std::numeric_limits<double>::infinity();

// The wall's lowest point along `up` (height = x . up), or -infinity when it moves or has no
// lowest point.
double lowest_point(const Wall& w, const Vec3& up) {
  if (!w.velocity.isZero() || w.motion.is_profile() || w.motion.spins) return kEndless;
  switch (w.shape) {
    case WallShape::Plane: {
      const Vec3 n = w.axis.normalized();
      return std::abs(n.dot(up)) >= 1.0 - 1e-12 ? w.point.dot(up) : kEndless;
    }
    case WallShape::Cylinder: {
      const Vec3 a = w.axis.normalized();
      const double along = std::abs(a.dot(up));
      return w.point.dot(up) - 0.5 * w.length * along - w.radius * std::sqrt(std::max(0.0, 1.0 - along * along));
    }
    case WallShape::Mesh: {
      double low = std::numeric_limits<double>::infinity();
      for (const auto& t : w.triangles)
        for (const auto& v : t) low = std::min(low, v.dot(up));
      return low;
    }
  }
  return kEndless;
}

}  // namespace

void check_bodies_reach_walls(const PlacedBodies& placed, const std::vector<BodySpec>& specs,
                              const std::vector<Wall>& walls, const Vec3& gravity) {
  const double g = gravity.norm();
  if (walls.empty() || !(g > 0)) return;
  const Vec3 up = -gravity / g;
  double floor = std::numeric_limits<double>::infinity();  // the lowest any wall comes
  std::size_t lowest = 0;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const double low = lowest_point(walls[w], up);
    if (low < floor) {
      floor = low;
      lowest = w;
    }
  }
  if (floor == kEndless) return;
  std::vector<double> top(placed.body_names.size(), kEndless);
  for (std::size_t k = 0; k < placed.all.position.size(); ++k) {
    const double rise = std::max(0.0, placed.velocity[k].dot(up));
    const double reach = placed.all.position[k].dot(up) + placed.all.radius[k] + rise * rise / (2 * g);
    double& t = top[static_cast<std::size_t>(placed.body[k])];
    t = std::max(t, reach);
  }
  for (std::size_t b = 0; b < top.size(); ++b) {
    if (!(top[b] < floor)) continue;
    const BodySpec& spec = specs[placed.spec_of[b]];
    throw SceneError(fmt::format(
        "{}: [[body]] '{}' can never meet a wall: it reaches at most {:.4g} m up (along -gravity: its top plus the "
        "rise its upward speed allows), below the lowest point of every wall (the lowest, wall '{}', reaches "
        "{:.4g} m), and gravity pulls it away; place it above a wall (position, stream start or region) or add a "
        "wall below it (docs/reference/materials.md)",
        spec.where, placed.body_names[b], top[b], walls[lowest].name, floor));
  }
}

}  // namespace shard::scene_detail
