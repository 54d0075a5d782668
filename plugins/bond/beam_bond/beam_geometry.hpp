#pragma once
// Kinematics of one beam bond in the total formulation (README.md, "Formulation"): everything is measured
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

// The deformed bond in its mid frame.
struct Deformation {
  Mat3 frame;       // Bm: bond frame -> lab
  Vec3 d_local;     // x2 - x1 in the bond frame
  Vec3 theta;       // relative rotation vector, bond frame
  Vec3 skew_axis;   // tan(|theta|/4)/(2|theta|) theta: the skew part of A1, A2
  double mu = 1;    // M on the plane normal to theta
  double mu_axis = 0;  // (1 - mu) / s^2 with s = sin(|theta|/2): M u = mu u + mu_axis (v.u) v
  Vec3 v;           // vector part of q_rel, s = |v|

  // M u: maps a bond-frame torque to the mid frame's conjugate of d theta (symmetric).
  Vec3 apply_m(const Vec3& u) const { return mu * u + mu_axis * v.dot(u) * v; }
};

// (arcsin s) / s = sum_n c_n s^(2n), c_n = C(2n, n) / (4^n (2n + 1)); below s^2 = 0.01 the terms
// up to n = 8 give mu and mu_axis to within 1e-17 relative (next term c_9 s^18 < 1e-18), so the
// common case of small bond rotations needs neither atan2 nor a division.
inline constexpr double kSeriesLimit = 0.01;  // s^2
// Estrin's scheme: the x86-64-v2 baseline has no FMA, and Horner's chain of 14 dependent
// operations was the longest latency in the bond loop.
inline double arcsin_ratio_tail(double s2) {  // (mu - 1) / s^2 = c_1 + c_2 s^2 + ... + c_8 s^14
  constexpr double c1 = 1.0 / 6, c2 = 3.0 / 40, c3 = 5.0 / 112, c4 = 35.0 / 1152, c5 = 63.0 / 2816,
                   c6 = 231.0 / 13312, c7 = 143.0 / 10240, c8 = 6435.0 / 557056;
  const double s4 = s2 * s2, s8 = s4 * s4;
  return ((c1 + c2 * s2) + s4 * (c3 + c4 * s2)) + s8 * ((c5 + c6 * s2) + s4 * (c7 + c8 * s2));
}

// 1 / |q| for a quaternion that is a product of unit quaternions: |q|^2 = 1 + e with |e| of a few
// ulp, where 1 - e/2 is exact to O(e^2); otherwise the square root.
inline double inverse_norm(double norm2) {
  const double e = norm2 - 1;
  return std::abs(e) < 1e-9 ? 1 - 0.5 * e : 1 / std::sqrt(norm2);
}

[[gnu::always_inline]] inline Deformation deform(const Reference& ref, const Vec3& x1, const Vec3& x2, const Quat& q1,
                          const Quat& q2) {
  const Quat frame1 = q1 * ref.frame_in_first;
  const Quat frame2 = q2 * ref.frame_in_second;
  Quat rel = frame1.conjugate() * frame2;
  // Shortest rotation (|theta| <= pi), normalised.
  const double scale = std::copysign(inverse_norm(rel.coeffs().squaredNorm()), rel.w());
  rel.coeffs() *= scale;
  Deformation g;
  g.v = rel.vec();
  const double s2 = g.v.squaredNorm();  // sin^2(|theta|/2)
  const double w = rel.w();             // cos(|theta|/2)
  if (s2 < kSeriesLimit) {
    const double tail = arcsin_ratio_tail(s2);
    g.mu = 1 + s2 * tail;
    g.mu_axis = -tail;
  } else {
    const double s = std::sqrt(s2);
    const double half_angle = std::atan2(s, w);
    g.mu = half_angle / s;
    g.mu_axis = (s - half_angle) / (s * s2);
  }
  g.theta = 2 * g.mu * g.v;
  // sqrt(q_rel) = (1 + w, v) / sqrt(2 (1 + w)); tan(t/4) = s / (1 + w) with t = |theta|.
  const double inv_root = 1 / std::sqrt(2 * (1 + w));
  g.skew_axis = (inv_root * inv_root) * g.v;
  const Quat half(inv_root * (1 + w), inv_root * g.v.x(), inv_root * g.v.y(), inv_root * g.v.z());
  g.frame = (frame1 * half).toRotationMatrix();
  g.d_local = g.frame.transpose() * (x2 - x1);
  return g;
}

// Gamma and kappa (see the header), from 1 / l0.
struct StrainCurvature {
  Vec3 strain, curvature;
};

inline StrainCurvature strain_curvature(const Deformation& g, double inv_l0) {
  return {g.d_local * inv_l0 - Vec3::UnitX(), g.theta * inv_l0};
}

// Rates conjugate to Gamma and kappa: v12 = l0 dGamma/dt and omega_rel = d theta/dt, both in the
// bond frame, from the lab velocities and spins of the two ends. Zero for rigid motion of the pair.
// v12 is only needed by a viscous force (eq. 4 with d > 0, Kelvin-Voigt); without `strain_rate` it
// is left zero and its matrix product and two cross products are not spent.
struct Rates {
  Vec3 v12 = Vec3::Zero();
  Vec3 omega_rel;
};

[[gnu::always_inline]] inline Rates rates_of(const Deformation& g, const Vec3& v1, const Vec3& v2, const Vec3& omega1,
                                             const Vec3& omega2, bool strain_rate = true) {
  const Mat3& R = g.frame;
  const Vec3 w1 = R.transpose() * omega1;
  const Vec3 w2 = R.transpose() * omega2;
  Rates r;
  r.omega_rel = g.apply_m(w2 - w1);
  if (strain_rate) {
    const Vec3 frame_spin = 0.5 * (w1 + w2) + g.skew_axis.cross(w1 - w2);
    r.v12 = R.transpose() * (v2 - v1) - frame_spin.cross(g.d_local);
  }
  return r;
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

  Vec3 torque(double second_moment, double inv_l0, double inertia1, double inertia2, const Vec3& omega_rel) const {
    const double inertia_r = inertia1 * inertia2 / (inertia1 + inertia2);
    const double c_bend = bend_scale_ * std::sqrt(second_moment * inertia_r * inv_l0);
    const double c_twist = c_bend * twist_over_bend_;
    return {c_twist * omega_rel.x(), c_bend * omega_rel.y(), c_bend * omega_rel.z()};
  }

 private:
  double bend_scale_, twist_over_bend_;
};

// Lab-frame loads on the two ends from the bond-frame force and bending/twisting torque: the force
// pair's couple C = d x F is split between the ends (plus the skew correction) so that no angular
// momentum is created. `swapped`: the batch lists the bond from its second end.
struct PairLoads {
  Vec3 force_on_i, torque_on_i, torque_on_j;
};

[[gnu::always_inline]] inline PairLoads pair_loads(const Deformation& g, const Vec3& force, const Vec3& torque, bool swapped) {
  const Mat3& R = g.frame;
  const Vec3 couple = g.d_local.cross(force);
  const Vec3 couple_skew = g.skew_axis.cross(couple);
  const Vec3 bend_twist = g.apply_m(torque);
  const Vec3 force_on_first = R * force;
  const Vec3 torque_on_first = R * (0.5 * couple - couple_skew + bend_twist);
  const Vec3 torque_on_second = R * (0.5 * couple + couple_skew - bend_twist);
  if (swapped) return {-force_on_first, torque_on_second, torque_on_first};
  return {force_on_first, torque_on_first, torque_on_second};
}

}  // namespace shard::beam
