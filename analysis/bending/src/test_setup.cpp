#include "shard/bending/test_setup.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace shard::bending {

BeamFrame beam_frame(const Vec3& pin_a, const Vec3& pin_b, const Vec3& down) {
  BeamFrame f;
  f.down = down.normalized();
  Vec3 axis = pin_b - pin_a;
  axis -= axis.dot(f.down) * f.down;
  if (axis.norm() == 0) throw std::invalid_argument("the two loading pins coincide across the load direction");
  f.axis = axis.normalized();
  if (f.axis.dot(Vec3::UnitX() + Vec3::UnitY() + Vec3::UnitZ()) < 0) f.axis = -f.axis;
  f.across = f.down.cross(f.axis).normalized();
  f.centre = 0.5 * (pin_a + pin_b);
  return f;
}

double distance_along(const BeamFrame& frame, const Vec3& a, const Vec3& b) { return std::abs((b - a).dot(frame.axis)); }

SphereExtent sphere_extent(const BeamFrame& frame, std::span<const Vec3> positions, std::span<const double> radii) {
  SphereExtent e;
  if (positions.empty()) return e;
  struct Band {
    double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  };
  auto band = [&](const Vec3& dir) {
    Band b;
    for (std::size_t k = 0; k < positions.size(); ++k) {
      const double s = (positions[k] - frame.centre).dot(dir);
      b.lo = std::min(b.lo, s - radii[k]);
      b.hi = std::max(b.hi, s + radii[k]);
    }
    return b;
  };
  const Band l = band(frame.axis), w = band(frame.across), h = band(frame.down);
  e.length = l.hi - l.lo;
  e.width = w.hi - w.lo;
  e.height = h.hi - h.lo;
  e.mid_height = 0.5 * (h.lo + h.hi);
  return e;
}

}  // namespace shard::bending
