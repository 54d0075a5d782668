#pragma once
// Shared numbers for the beam bond tests: the seed's Table I particle and bond.
#include <cmath>
#include <numbers>

#include "beam_bond_model.hpp"
#include "bond_pair.hpp"

namespace shard::test {

inline constexpr double kRadius = 0.35e-3;   // m, d_min / 2 (Table I)
inline constexpr double kDensity = 3720;     // kg/m^3 (Table I)

// Section and stiffnesses of a bond between two spheres of radius kRadius (lambda = 1).
struct BeamNumbers {
  double E, G, a_s, r_b, A, J, l0;
  double axial() const { return E * A / l0; }         // N/m
  double shear() const { return a_s * G * A / l0; }   // N/m
  double twist() const { return 2 * G * J / l0; }     // N m/rad
  double bending() const { return E * J / l0; }       // N m/rad
};

inline BeamNumbers numbers_of(const beam::BeamBondParams& p, double radius = kRadius) {
  BeamNumbers n;
  n.E = p.youngs_modulus;
  n.G = p.effective_shear_modulus();
  n.a_s = p.shear_coefficient;
  n.r_b = p.radius_ratio * radius;
  n.A = std::numbers::pi * n.r_b * n.r_b;
  n.J = std::numbers::pi * std::pow(n.r_b, 4) / 4;
  n.l0 = 2 * radius;
  return n;
}

inline Quat rotation(const Vec3& rotation_vector) {
  const double angle = rotation_vector.norm();
  if (angle == 0) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, rotation_vector / angle));
}

// Turns particle k by a lab-frame rotation vector.
inline void turn(HandBonds& w, Index k, const Vec3& rotation_vector) {
  w.orientation[k] = (rotation(rotation_vector) * w.orientation[k]).normalized();
}

// Two touching Table I spheres bonded along `axis`, with non-trivial initial orientations so
// that no test relies on identity quaternions.
inline HandBonds touching_pair(const Vec3& axis = Vec3(1, 2, -0.5)) {
  HandBonds w;
  const Vec3 centre(0.01, -0.02, 0.003);
  const Vec3 n = axis.normalized();
  w.add_sphere(centre - kRadius * n, kRadius, kDensity);
  w.add_sphere(centre + kRadius * n, kRadius, kDensity);
  w.orientation[0] = rotation(Vec3(0.3, -1.1, 0.7));
  w.orientation[1] = rotation(Vec3(-2.0, 0.4, 0.9));
  w.add_bond(0, 1);
  return w;
}

}  // namespace shard::test
