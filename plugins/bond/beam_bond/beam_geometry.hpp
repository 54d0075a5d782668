#pragma once
// The bonded reference configuration of a beam bond (its state) and the quantities the law
// (beam_law.hpp) evaluates, in the total formulation (README.md, "Formulation"): everything is measured
// from the bonded reference configuration, so rigid motions of the pair produce no strain.
//
// Frames. At bonding the bond frame B0 (x along the centre line from the first to the second
// particle) is stored in the body frame of each particle: b1 = q1^-1 B0, b2 = q2^-1 B0. Later each
// particle carries its own copy, B1 = q1 b1 and B2 = q2 b2. Their relative rotation is
//   q_rel = B1^-1 B2 = exp(theta / 2)   (rotation vector theta, the same components in B1 and B2),
// and the bond frame used for everything below is the mid rotation
//   Bm = B1 exp(theta / 2) = B2 exp(-theta / 2),
// which does not prefer either particle.
//
// Strain and curvature (the seed's Gamma and kappa):
//   Gamma = Bm^T (x2 - x1) / l0 - e_x   (axial strain; two shear strains: bond-line rotation
//                                        relative to the mean particle rotation)
//   kappa = theta / l0                   (twist about x; two bending curvatures)
// For small motions this is the two-node Timoshenko element with one-point integration:
// Gamma_y = (u2y - u1y) / l0 - (phi1z + phi2z) / 2,  kappa_z = (phi2z - phi1z) / l0.
//
// Elastic energy U = l0/2 (Gamma . F + kappa . T), F = K_F Gamma, T = K_T kappa (eq. 3, 5).
// Forces and torques are the exact derivatives of U with respect to the particle positions and
// lab-frame rotations; with the identities
//   d theta = M Bm^T (dphi2 - dphi1),        M = I + (mu - 1) P,  mu = (|theta|/2) / sin(|theta|/2)
//   d(Bm)   = rotation by Bm (A1 Bm^T dphi1 + A2 Bm^T dphi2),  A1,2 = I/2 +- tan(|theta|/4)/(2|theta|) [theta]x
// (P projects normal to theta) this gives, in the bond frame, with the couple C = d_local x F:
//   force on 1 = Bm F,                   force on 2 = -Bm F
//   torque on 1 = Bm (A1^T C + M T),     torque on 2 = Bm (A2^T C - M T).
// The couple of the shear force is split half and half (plus a skew part of order |theta|
// that keeps the split exact), and torque1 + torque2 + (x1 - x2) x F = 0: no angular momentum
// is created. Because U is a function of the configuration only, an undamped pair conserves
// energy, and U is unchanged when the two particles trade places (the swapped bond frame is Bm
// turned half a turn about z, under which the diagonal stiffnesses are invariant).
#include <cmath>
#include <cstddef>

#include <algorithm>
#include <numbers>

#include "shard/particles.hpp"
#include "shard/types.hpp"

namespace shard::beam {

// The bond's own "first" particle is the one with the smaller stable id, so the state stays
// valid when the kernel reorders particles or lists a bond the other way round, and a swapped
// bond runs exactly the same arithmetic.
struct Ends {
  Index first, second;
  bool swapped;  // first is batch.j
};

inline Ends ends_of(const ParticleView& p, Index i, Index j) {
  const bool swapped = p.id ? p.id[j] < p.id[i] : j < i;
  return swapped ? Ends{j, i, true} : Ends{i, j, false};
}

// The bond's cross-section (eq. 3-5): radius lambda min(r1, r2).
struct Section {
  double radius, area, second_moment;  // r_b, A_b = pi r_b^2, J_b = pi r_b^4 / 4
};

inline Section section_of(double lambda, double r1, double r2) {
  const double r = lambda * std::min(r1, r2);
  return {r, std::numbers::pi * r * r, std::numbers::pi * r * r * r * r / 4};
}

// Per-bond state in the kernel array: l0, then b1 and b2 as (w, x, y, z).
inline constexpr std::size_t kStateSize = 9;

struct Reference {
  double l0 = 0;                   // m, centre distance at bonding
  Quat frame_in_first = Quat::Identity();   // b1
  Quat frame_in_second = Quat::Identity();  // b2
};

inline void store(double* s, const Reference& r) {
  s[0] = r.l0;
  s[1] = r.frame_in_first.w();
  s[2] = r.frame_in_first.x();
  s[3] = r.frame_in_first.y();
  s[4] = r.frame_in_first.z();
  s[5] = r.frame_in_second.w();
  s[6] = r.frame_in_second.x();
  s[7] = r.frame_in_second.y();
  s[8] = r.frame_in_second.z();
}

inline Reference load(const double* s) {
  return {s[0], Quat(s[1], s[2], s[3], s[4]), Quat(s[5], s[6], s[7], s[8])};
}

// The shortest rotation taking e_x onto the unit vector n (half a turn about z when n = -e_x).
inline Quat frame_along(const Vec3& n) {
  if (n.x() < -1 + 1e-12) return Quat(0, 0, 0, 1);
  return Quat(1 + n.x(), 0, -n.z(), n.y()).normalized();  // (1 + e_x . n, e_x x n)
}

// Records the bonded configuration: B0 turns e_x onto the centre line.
inline Reference reference_of(const Vec3& x1, const Vec3& x2, const Quat& q1, const Quat& q2) {
  const Vec3 line = x2 - x1;
  const Quat frame = frame_along(line.normalized());
  return {line.norm(), (q1.conjugate() * frame).normalized(), (q2.conjugate() * frame).normalized()};
}

// Eq. 6-7: viscous torque on omega_rel with coefficients sqrt(k I_r), k the twist (2 G J / l0) and
// bending (E J / l0) stiffness, I_r = I1 I2 / (I1 + I2); `factor` scales the seed's coefficients.
// The material factors are taken out of the per-bond square root: c_bend = factor sqrt(E) sqrt(J I_r / l0),
// c_twist = c_bend sqrt(2 G / E).
class RotationalDamping {
 public:
  RotationalDamping(double factor, double youngs, double shear)
      : bend_scale_(factor * std::sqrt(youngs)), twist_over_bend_(std::sqrt(2 * shear / youngs)) {}

  double bend_scale() const { return bend_scale_; }            // factor sqrt(E)
  double twist_over_bend() const { return twist_over_bend_; }  // sqrt(2 G / E)

 private:
  double bend_scale_, twist_over_bend_;
};

}  // namespace shard::beam
