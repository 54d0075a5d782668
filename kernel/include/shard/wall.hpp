#pragma once
// Rigid walls with prescribed motion (wall_motion.hpp). Each records the force and torque the particles exert
// on it and its own displacement, so loading pins and supports are force sensors.
#include <array>
#include <string>
#include <vector>

#include "shard/types.hpp"
#include "shard/wall_motion.hpp"

namespace shard {

enum class WallShape { Plane, Cylinder, Mesh };

struct Wall {
  std::string name;
  WallShape shape = WallShape::Plane;
  // Plane: a point on it and the unit normal pointing into the particles' side.
  // Cylinder: a point on the axis (the centre of the finite cylinder), the unit axis, the radius
  //   and the length; particles touch its outer surface (a pin or roller).
  // Mesh: triangles in lab coordinates at displacement zero; both faces are solid.
  Vec3 point = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();  // plane normal or cylinder axis
  double radius = 0;
  double length = 0;
  std::vector<std::array<Vec3, 3>> triangles;

  // Prescribed motion. Without a ramp or table, `velocity` is constant and `displacement` the sum
  // of the steps; with one (motion.is_profile()), both are set from motion at every step.
  WallMotion motion;
  Vec3 velocity = Vec3::Zero();      // now, m/s
  Vec3 displacement = Vec3::Zero();  // since the start, m
  Vec3 force = Vec3::Zero();         // received from particles this step, N
  Vec3 torque = Vec3::Zero();        // about `point` (+ displacement), N m
};

// Closest point of the wall surface to x and the distance along the outward normal; returns
// false when x is outside the wall's reach (beyond the cylinder ends, outside every triangle's
// distance `max_gap`). `normal` points from the wall towards x.
bool wall_contact(const Wall& wall, const Vec3& x, double max_gap, Vec3& normal, double& distance);

}  // namespace shard
