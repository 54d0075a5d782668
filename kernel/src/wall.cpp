#include "shard/wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shard {
namespace {

// Closest point on triangle (a, b, c) to p, by Voronoi regions of the vertices, edges and face.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// The contact geometry with the wall's shape offset by `shift` (its displacement; zero in the frame
// of a spinning wall).
bool contact_shifted(const Wall& wall, const Vec3& x, const Vec3& shift, double max_gap, Vec3& normal,
                     double& distance) {
  const Vec3 origin = wall.point + shift;
  switch (wall.shape) {
    case WallShape::Plane: {
      distance = (x - origin).dot(wall.axis);
      normal = wall.axis;
      return distance <= max_gap;
    }
    case WallShape::Cylinder: {
      const Vec3 rel = x - origin;
      const double along = rel.dot(wall.axis);
      if (std::abs(along) > 0.5 * wall.length) return false;
      const Vec3 radial = rel - along * wall.axis;
      const double rho = radial.norm();
      if (rho == 0.0) return false;
      normal = radial / rho;
      distance = rho - wall.radius;
      return distance <= max_gap;
    }
    case WallShape::Mesh: {
      double best = std::numeric_limits<double>::infinity();
      Vec3 best_point = Vec3::Zero();
      for (const auto& t : wall.triangles) {
        const Vec3 q = closest_point_on_triangle(x, t[0] + shift, t[1] + shift, t[2] + shift);
        const double d2 = (x - q).squaredNorm();
        if (d2 < best) {
          best = d2;
          best_point = q;
        }
      }
      distance = std::sqrt(best);
      if (!(distance <= max_gap) || distance == 0.0) return false;
      normal = (x - best_point) / distance;
      return true;
    }
  }
  return false;
}

}  // namespace

// A spinning wall is not turned: the particle is carried into the wall's frame (one 3x3 product),
// touched against the geometry as read, and the normal carried back.
bool wall_contact(const Wall& wall, const Vec3& x, double max_gap, Vec3& normal, double& distance) {
  if (!wall.motion.spins) return contact_shifted(wall, x, wall.displacement, max_gap, normal, distance);
  const Vec3 local = wall.motion.spin_centre + wall.rotation.transpose() * (x - wall.centre());
  Vec3 local_normal;
  if (!contact_shifted(wall, local, Vec3::Zero(), max_gap, local_normal, distance)) return false;
  normal = wall.rotation * local_normal;
  return true;
}

Vec3 Wall::surface_velocity_at(const Vec3& x, const Vec3& n) const {
  Vec3 v = velocity;
  if (motion.spins) v += angular_speed * motion.spin_axis.cross(x - centre());
  if (!surface_velocity.isZero()) {
    const Vec3 belt = rotation * surface_velocity;
    v += belt - belt.dot(n) * n;  // a belt slides along the surface, never into it
  }
  return v;
}

bool Wall::turn_moves_surface() const {
  if (!motion.spins) return false;
  // Unit vectors: parallel to 1e-12 rad; the centre within 1e-12 of the radius off the axis.
  const Vec3 along = axis.normalized();
  const bool parallel = motion.spin_axis.cross(along).norm() < 1e-12;
  if (shape == WallShape::Plane) return !parallel;
  if (shape == WallShape::Cylinder) {
    const Vec3 off = motion.spin_centre - point;
    return !(parallel && (off - off.dot(along) * along).norm() <= 1e-12 * radius);
  }
  return true;  // a mesh: a faceted drum is not turn-invariant
}

namespace {

void set_rotation(Wall& wall, double t) {
  if (!wall.motion.spins) return;
  wall.angle = wall.motion.angle_at(t);
  wall.angular_speed = wall.motion.angular_speed_at(t);
  wall.rotation = Eigen::AngleAxisd(wall.angle, wall.motion.spin_axis).toRotationMatrix();
}

}  // namespace

void move_wall(Wall& wall, double t, double dt) {
  if (wall.motion.is_profile()) {
    wall.displacement = wall.motion.displacement_at(t);
    wall.velocity = wall.motion.velocity_at(t);
  } else {
    wall.displacement += dt * wall.velocity;
  }
  set_rotation(wall, t);
}

double cylinder_touch_offset(const Wall& w, const Vec3& n, const Vec3& x, double r, bool first) {
  if (w.shape != WallShape::Cylinder) return std::numeric_limits<double>::quiet_NaN();
  const Vec3 a = w.axis.normalized();
  Vec3 d = x - w.point;
  if (std::abs(d.dot(a)) > 0.5 * w.length + r) return std::numeric_limits<double>::quiet_NaN();
  d -= d.dot(a) * a;
  const Vec3 n_perp = (n - n.dot(a) * a).normalized();
  const double along = d.dot(n_perp);
  const double lateral2 = (d - along * n_perp).squaredNorm();
  const double reach2 = (w.radius + r) * (w.radius + r);
  if (lateral2 >= reach2) return std::numeric_limits<double>::quiet_NaN();
  const double h = std::sqrt(reach2 - lateral2);
  return first ? along - h : along + h;
}

void place_wall(Wall& wall, double t) {
  if (wall.motion.is_profile()) {  // a ramp starts at rest
    wall.displacement = wall.motion.displacement_at(t);
    wall.velocity = wall.motion.velocity_at(t);
  }
  set_rotation(wall, t);
}

}  // namespace shard
