#pragma once
// Kinematics of the foreign spring bond (test-only): what LAMMPS bpm/rotational
// and YADE's cohesive law measure, written here without Shard's beam code. The pair's relative
// motion since bonding is split into a normal stretch, a shear offset of the second particle from
// the bond direction the two particles' frames agree on, and a relative rotation split into
// bending (perpendicular to the bond) and twisting (about it). A rigid motion of the pair gives
// zero for all four.
#include <cmath>

#include "shard/types.hpp"

namespace shard::foreign {

// The bonded reference: rest length, the bond direction as seen from each particle's body frame,
// and the relative orientation of the two particles.
struct SpringReference {
  double rest_length = 0;     // m
  Vec3 direction_first;       // unit, body frame of the first particle
  Vec3 direction_second;      // unit, body frame of the second particle
  Quat relative = Quat::Identity();  // first^-1 * second at bonding
};

inline SpringReference spring_reference(const Vec3& x1, const Vec3& x2, const Quat& q1, const Quat& q2) {
  SpringReference ref;
  const Vec3 d = x2 - x1;
  ref.rest_length = d.norm();
  const Vec3 n = d / ref.rest_length;
  ref.direction_first = q1.conjugate() * n;
  ref.direction_second = q2.conjugate() * n;
  ref.relative = q1.conjugate() * q2;
  return ref;
}

// Rotation vector (axis times angle, rad) of a unit quaternion, the shorter way round.
inline Vec3 rotation_vector(Quat q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Vec3 v = q.vec();
  const double s = v.norm();
  // Below 1e-8 the series 2 v (1 + s^2/6 ...) is exact to rounding; atan2 would lose digits.
  if (s < 1e-8) return 2 * v;
  return v * (2 * std::atan2(s, q.w()) / s);
}

struct SpringMotion {
  Vec3 normal;         // current unit bond direction, first -> second
  double length = 0;   // m, current centre distance
  double stretch = 0;  // m, length - rest_length (> 0 in tension)
  Vec3 shear;          // m, offset of the second particle across the bond (perpendicular to normal)
  Vec3 bending;        // rad, relative rotation perpendicular to the bond
  Vec3 twisting;       // rad, relative rotation about the bond
};

inline SpringMotion spring_motion(const SpringReference& ref, const Vec3& x1, const Vec3& x2, const Quat& q1,
                                  const Quat& q2) {
  SpringMotion m;
  const Vec3 d = x2 - x1;
  m.length = d.norm();
  m.normal = d / m.length;
  m.stretch = m.length - ref.rest_length;
  // The direction both particles' frames carry along, averaged; the second particle's offset from
  // it, across the current bond, at the rest length (the shear "displacement" of a bpm bond).
  const Vec3 carried = (q1 * ref.direction_first + q2 * ref.direction_second).normalized();
  m.shear = -ref.rest_length * (carried - carried.dot(m.normal) * m.normal);
  // Rotation of the second particle away from where a rigid pair would have carried it.
  const Vec3 theta = rotation_vector((q2 * ref.relative.conjugate() * q1.conjugate()).normalized());
  m.twisting = theta.dot(m.normal) * m.normal;
  m.bending = theta - m.twisting;
  return m;
}

}  // namespace shard::foreign
