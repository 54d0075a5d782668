#pragma once
// Meshes and particles for the spinning and belt wall tests, built in code.
#include <cmath>
#include <numbers>

#include "shard/wall.hpp"

namespace shard::test {

// The side of a closed drum: a prism of `sides` flat faces inscribed in a circle of `radius`
// about the y axis through the origin, `length` long; ends open.
inline Wall drum_mesh(double radius, double length, int sides) {
  Wall w;
  w.name = "drum";
  w.shape = WallShape::Mesh;
  const double y = 0.5 * length;
  for (int k = 0; k < sides; ++k) {
    const double a0 = 2 * std::numbers::pi * k / sides, a1 = 2 * std::numbers::pi * (k + 1) / sides;
    const Vec3 p0(radius * std::cos(a0), -y, radius * std::sin(a0)), p1(radius * std::cos(a1), -y, radius * std::sin(a1));
    const Vec3 q0 = p0 + Vec3(0, length, 0), q1 = p1 + Vec3(0, length, 0);
    w.triangles.push_back({p0, p1, q1});
    w.triangles.push_back({p0, q1, q0});
  }
  return w;
}

// A flat rectangular paddle in the plane y = 0, x in [0, reach], z in [-half_height, half_height].
inline Wall paddle_mesh(double reach, double half_height) {
  Wall w;
  w.name = "paddle";
  w.shape = WallShape::Mesh;
  const Vec3 a(0, 0, -half_height), b(reach, 0, -half_height), c(reach, 0, half_height), d(0, 0, half_height);
  w.triangles.push_back({a, b, c});
  w.triangles.push_back({a, c, d});
  return w;
}

// Turns the wall about `axis` through `centre` at `omega` rad/s from the start.
inline void spin(Wall& w, const Vec3& centre, const Vec3& axis, double omega) {
  w.motion.spins = true;
  w.motion.spin_centre = centre;
  w.motion.spin_axis = axis.normalized();
  w.motion.angular_speed = omega;
}

}  // namespace shard::test
