#pragma once
// Rigid walls with prescribed motion (wall_motion.hpp): translation, rotation about an axis, and a
// surface that slides over a fixed geometry (a conveyor belt). Each records the force and torque the
// particles exert on it, its own displacement, and the energy its contacts dissipate and their
// number (a wear indicator), so loading pins and supports are force sensors.
#include <array>
#include <cstdint>
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
  // A spinning wall (motion.spins) keeps this geometry in its own frame, the lab at time zero;
  // the lab position of a wall point y is centre() + rotation (y - motion.spin_centre).
  Vec3 point = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();  // plane normal or cylinder axis
  double radius = 0;
  double length = 0;
  std::vector<std::array<Vec3, 3>> triangles;
  // The scene material it is made of (docs/reference/materials.md); read only when the scene has several.
  std::int32_t material = 0;
  // Bonds between particles whose centres start within this distance of the surface never fail
  // (unbreakable_zone.hpp), m; 0: none.
  double unbreakable_zone = 0;

  // Prescribed motion. Without a ramp or table, `velocity` is constant and `displacement` the sum
  // of the steps; with one (motion.is_profile()), both are set from motion at every step.
  WallMotion motion;
  Vec3 velocity = Vec3::Zero();      // now, m/s
  Vec3 displacement = Vec3::Zero();  // since the start, m
  Vec3 force = Vec3::Zero();         // received from particles this step, N
  Vec3 torque = Vec3::Zero();        // about `point` (+ displacement), or centre() when spinning, N m

  // Rotation now, set from motion at every step (identity without a spin).
  double angle = 0;          // rad about motion.spin_axis since the start
  double angular_speed = 0;  // rad/s
  Mat3 rotation = Mat3::Identity();

  // Conveyor belt: the velocity of the surface over its fixed geometry, m/s, in the wall's frame.
  // Only its part along the surface acts (a plane's is checked to lie in the plane).
  Vec3 surface_velocity = Vec3::Zero();

  // Wear indicator, summed over the wall's contacts since the start: the work of the contact forces
  // on the particles' motion relative to the surface (J, positive when the particles lose energy),
  // what of it is still stored elastically in the contacts now, and the contacts begun.
  double contact_work = 0;
  double stored_energy = 0;
  std::int64_t impacts = 0;

  // The energy dissipated in the wall's contacts so far (damping and sliding), J.
  double impact_energy() const { return contact_work - stored_energy; }
  // The point the rotation axis passes through now.
  Vec3 centre() const { return motion.spin_centre + displacement; }
  // True when the surface's velocity varies over the wall (a spin) or differs from the wall's
  // own velocity (a belt): the contact then asks surface_velocity_at.
  bool surface_moves() const { return motion.spins || !surface_velocity.isZero(); }
  // Velocity of the wall's surface at the lab point x where the outward unit normal is n.
  Vec3 surface_velocity_at(const Vec3& x, const Vec3& n) const;
  // False when the turn leaves the surface where it is (a plane turning about its normal, a
  // cylinder about its own axis): only its velocity changes, and the neighbour list need not follow.
  bool turn_moves_surface() const;
  // Angular velocity now, rad/s (lab frame).
  Vec3 angular_velocity() const { return angular_speed * motion.spin_axis; }
};

// Sets the wall's displacement, velocity and rotation for time t, dt after the last call (a constant
// velocity is summed step by step, a profile evaluated at t).
void move_wall(Wall& wall, double t, double dt);
// Sets the wall's pose at time t without stepping (the start of a run and a restore): a profile
// and the rotation from t; a constant velocity keeps the displacement it has.
void place_wall(Wall& wall, double t);

// Offset s along the unit direction n at which a cylinder wall (axis a, radius R, centre at its point
// + s n) touches the sphere (x, r): the two roots of |(x - point - s n)_perp| = R + r. `first` is the
// smaller root (the wall arriving from -n), otherwise the larger one; NaN when the sphere is beside
// it or the wall is no cylinder. How far a pin is brought down onto a specimen to seat it.
double cylinder_touch_offset(const Wall& wall, const Vec3& n, const Vec3& x, double r, bool first);

// Closest point of the wall surface to x and the distance along the outward normal; returns
// false when x is outside the wall's reach (beyond the cylinder ends, outside every triangle's
// distance `max_gap`). `normal` points from the wall towards x.
bool wall_contact(const Wall& wall, const Vec3& x, double max_gap, Vec3& normal, double& distance);

}  // namespace shard
