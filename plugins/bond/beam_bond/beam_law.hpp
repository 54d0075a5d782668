#pragma once
// beam_bond's law (README.md, "Formulation"), written once for any lane type T
// (shard/lanes/lanes.hpp): T = double evaluates one bond and is the scalar reference; T =
// xsimd::batch<double, A> evaluates one bond per SIMD lane (beam_block.hpp). The effect policies
// (effects/) are composed in by template flags, in this order: the Maxwell arm advanced over the
// step (its strains join Gamma and kappa in the breakage check), the bond's own strength,
// softening instead of a break, the compressive axial modulus, the arm's force, torque and energy,
// the damage scaling all of them. Each is exact at its neutral value.
//
// The common case runs at every width: q_rel within 1e-9 of unit length, a rotation inside the
// arcsin series range, a bond the von Mises bound says cannot break (nor the extra criterion),
// an undamaged bond. The rare cases (1 / sqrt of an off-unit norm, atan2 beyond the series, the
// break decision, the softening damage) are written here too but run at width 1 only: a SIMD lane
// that needs one is flagged `fallback` and its bond is evaluated again by the width-1
// instantiation. No operation is fused (the sources are compiled with -ffp-contract=off) and every
// sum is written in one fixed order, so a bond gives the same bits at every width.
//
// The sums follow the order Eigen 3.4 evaluated the former per-bond helpers in (its SSE quaternion
// product; rows 0-1 of a 3x3 product summed (a0 + a1) + a2, row 2 a0 + (a1 + a2)), which keeps
// every result of the runs recorded before this law was written (docs/explanation/performance.md, state_hash).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "beam_geometry.hpp"
#include "beam_stress.hpp"
#include "effects/bond_effects.hpp"
#include "effects/cohesive_softening.hpp"
#include "effects/compression_asymmetry.hpp"
#include "shard/lanes/lanes.hpp"

namespace shard::beam {

// (arcsin s) / s = sum_n c_n s^(2n), c_n = C(2n, n) / (4^n (2n + 1)); below s^2 = 0.01 the terms
// up to n = 8 give mu and mu_axis to within 1e-17 relative (next term c_9 s^18 < 1e-18), so the
// common case of small bond rotations needs neither atan2 nor a division.
inline constexpr double kSeriesLimit = 0.01;  // s^2
// (mu - 1) / s^2 = c_1 + c_2 s^2 + ... + c_8 s^14 by Estrin's scheme (shorter dependency chain
// than Horner's without FMA).
template <class T>
inline T arcsin_ratio_tail(const T& s2) {
  constexpr double c1 = 1.0 / 6, c2 = 3.0 / 40, c3 = 5.0 / 112, c4 = 35.0 / 1152, c5 = 63.0 / 2816,
                   c6 = 231.0 / 13312, c7 = 143.0 / 10240, c8 = 6435.0 / 557056;
  const T s4 = s2 * s2, s8 = s4 * s4;
  return ((c1 + c2 * s2) + s4 * (c3 + c4 * s2)) + s8 * ((c5 + c6 * s2) + s4 * (c7 + c8 * s2));
}

// 1 / |q| from |q|^2 for a quaternion that is a product of unit quaternions: |q|^2 = 1 + e with
// |e| of a few ulp, where 1 - e/2 is exact to O(e^2). `unit` is false where |e| >= 1e-9; there
// the width-1 law takes 1 / sqrt(|q|^2) and a SIMD lane falls back.
template <class T, bool full>
inline T inverse_norm(const T& norm2, typename lanes::Lanes<T>::mask& unit) {
  using namespace lanes;
  const T e = norm2 - 1;
  unit = abs(e) < 1e-9;
  T inverse = 1 - 0.5 * e;
  if constexpr (full)
    if (!unit) inverse = 1 / std::sqrt(norm2);
  return inverse;
}

// M's factors from s^2 = sin^2(|theta|/2) and w = cos(|theta|/2): mu = (|theta|/2) / s and
// mu_axis = (1 - mu) / s^2, by the series where s^2 < kSeriesLimit (returned true), by atan2
// beyond it at width 1 (a SIMD lane there falls back).
template <class T, bool full>
inline typename lanes::Lanes<T>::mask rotation_factors(const T& s2, const T& w, T& mu, T& mu_axis) {
  const typename lanes::Lanes<T>::mask series = s2 < kSeriesLimit;
  const T tail = arcsin_ratio_tail(s2);
  mu = 1 + s2 * tail;
  mu_axis = -tail;
  if constexpr (full)
    if (!series) {
      const double s = std::sqrt(s2);
      const double half_angle = std::atan2(s, w);
      mu = half_angle / s;
      mu_axis = (s - half_angle) / (s * s2);
    }
  return series;
}

template <class T>
struct QuatLanes {
  T w, x, y, z;
};

// The quaternion product with Eigen 3.4's SSE grouping of the terms.
template <class T>
[[gnu::always_inline]] inline QuatLanes<T> product(const QuatLanes<T>& a, const QuatLanes<T>& b) {
  return {(a.w * b.w - a.y * b.y) - (a.z * b.z + a.x * b.x), (a.w * b.x + a.y * b.z) - (a.z * b.y - a.x * b.w),
          (a.w * b.y + a.y * b.w) + (a.z * b.x - a.x * b.z), (a.w * b.z - a.y * b.x) + (a.z * b.w + a.x * b.y)};
}

// The parameters as the law reads them (set once per model; the arm's factors per batch).
struct LawConstants {
  double youngs = 0, shear = 0, shear_coefficient = 0, radius_ratio = 0, damping = 0, strength = 0;
  double bend_scale = 0, twist_over_bend = 0;  // RotationalDamping's factors
  bool breakage = true;
  bool viscous_force = false;  // damping != 0: v12 is needed
  bool effects = false;        // the effects variant (strength and damage in the state)
  bool arm = false;            // effects with the Maxwell arm (viscosity_time > 0)
  double compression_modulus = 0;      // r E_b
  double arm_decay = 1, arm_gain = 0;  // MaxwellArm over this batch's step
  double arm_modulus_ratio = 1;        // beta: the arm spring's energy is E_b h^2 / (2 beta)
  double softening_ratio = 0;          // s of cohesive_softening.hpp (read at width 1)
};

// W bonds, one per lane, in the bond's own order (first = smaller stable id).
template <class T>
struct BondLanes {
  QuatLanes<T> q1, q2;
  T x1[3], x2[3], v1[3], v2[3], w1[3], w2[3];  // position, velocity, spin (lab)
  T r1, r2, i1, i2;                            // radius, moment of inertia
  T state[kViscousStateSize];                  // the first state_size() doubles are read
};

template <class T>
struct BondLoads {
  T force[3];                           // on the first end, lab frame (the second gets -force)
  T torque_first[3], torque_second[3];  // lab frame
  T energy;
  typename lanes::Lanes<T>::mask fallback;  // lanes the width-1 law must evaluate instead
  T next_arm[12];  // with the arm: the new previous (Gamma, kappa) and arm strains (h_Gamma, h_kappa)
  // Width 1 only: the break decision, the stresses at failure, and the new damage (softening).
  bool broken = false;
  BondStress stress;
  double damage = 0;
};

// No criterion beyond the von Mises strength (beam_bond's own). An extra criterion (e.g. the
// tutorial's crushing, docs/tutorials/crushing_bond) supplies a bound that is false only when it
// certainly does not break (any width) and the decision itself (width 1), both on Gamma, kappa.
struct NoExtraCriterion {
  template <class T>
  typename lanes::Lanes<T>::mask may_break(const T (&)[3], const T (&)[3], const T&, const LawConstants&) const {
    return typename lanes::Lanes<T>::mask(false);
  }
  bool breaks(const double (&)[3], const double (&)[3], const BondStress&, const LawConstants&) const { return false; }
};

// The law. `full`: width 1, with the rare cases; otherwise they set `fallback`.
template <class T, bool full, bool breakage, bool viscous, bool effects, bool arm, class Extra>
[[gnu::always_inline]] inline BondLoads<T> beam_law(const BondLanes<T>& in, const LawConstants& c, const Extra& extra) {
  using namespace lanes;
  using Mask = typename Lanes<T>::mask;
  const T* s = in.state;
  BondLoads<T> out;

  // The frames of the two ends, their relative rotation q_rel, normalised, shortest (|theta| <= pi).
  const QuatLanes<T> f1 = product(in.q1, {s[1], s[2], s[3], s[4]});
  const QuatLanes<T> f2 = product(in.q2, {s[5], s[6], s[7], s[8]});
  QuatLanes<T> rel = product(QuatLanes<T>{f1.w, -f1.x, -f1.y, -f1.z}, f2);
  const T norm2 = (rel.x * rel.x + rel.z * rel.z) + (rel.y * rel.y + rel.w * rel.w);
  Mask unit;
  const T scale = copysign(inverse_norm<T, full>(norm2, unit), rel.w);
  rel = {rel.w * scale, rel.x * scale, rel.y * scale, rel.z * scale};
  const T vx = rel.x, vy = rel.y, vz = rel.z, w = rel.w;
  // theta = 2 mu v, with M u = mu u + mu_axis (v.u) v (README.md).
  const T s2 = (vx * vx + vy * vy) + vz * vz;  // sin^2(|theta| / 2)
  T mu, mu_axis;
  const Mask series = rotation_factors<T, full>(s2, w, mu, mu_axis);
  const T two_mu = 2 * mu;
  const T thx = two_mu * vx, thy = two_mu * vy, thz = two_mu * vz;
  // sqrt(q_rel) = (1 + w, v) / sqrt(2 (1 + w)); the skew axis tan(|theta|/4) / (2 |theta|) theta.
  const T one_w = 1 + w;
  const T inv_root = 1 / sqrt(2 * one_w);
  const T k2 = inv_root * inv_root;
  const T skx = k2 * vx, sky = k2 * vy, skz = k2 * vz;
  // The mid frame Bm = B1 sqrt(q_rel) as a rotation matrix R (bond frame -> lab).
  const QuatLanes<T> m = product(f1, {inv_root * one_w, inv_root * vx, inv_root * vy, inv_root * vz});
  const T tx = 2 * m.x, ty = 2 * m.y, tz = 2 * m.z;
  const T twx = tx * m.w, twy = ty * m.w, twz = tz * m.w;
  const T txx = tx * m.x, txy = ty * m.x, txz = tz * m.x;
  const T tyy = ty * m.y, tyz = tz * m.y, tzz = tz * m.z;
  const T R00 = 1 - (tyy + tzz), R01 = txy - twz, R02 = txz + twy;
  const T R10 = txy + twz, R11 = 1 - (txx + tzz), R12 = tyz - twx;
  const T R20 = txz - twy, R21 = tyz + twx, R22 = 1 - (txx + tyy);
  // R^T u and R u (Eigen's order: see the header).
  auto to_bond = [&](const T& ux, const T& uy, const T& uz, T (&r)[3]) {
    r[0] = (R00 * ux + R10 * uy) + R20 * uz;
    r[1] = (R01 * ux + R11 * uy) + R21 * uz;
    r[2] = (R02 * ux + R12 * uy) + R22 * uz;
  };
  auto to_lab = [&](const T& ux, const T& uy, const T& uz, T (&r)[3]) {
    r[0] = (R00 * ux + R01 * uy) + R02 * uz;
    r[1] = (R10 * ux + R11 * uy) + R12 * uz;
    r[2] = R20 * ux + (R21 * uy + R22 * uz);
  };
  T dl[3];  // x2 - x1 in the bond frame
  to_bond(in.x2[0] - in.x1[0], in.x2[1] - in.x1[1], in.x2[2] - in.x1[2], dl);

  // Strain Gamma = d_local / l0 - e_x and curvature kappa = theta / l0; the section.
  const T l0 = s[0];
  const T inv_l0 = 1 / l0;
  const T strain[3] = {dl[0] * inv_l0 - 1, dl[1] * inv_l0, dl[2] * inv_l0};
  const T curvature[3] = {thx * inv_l0, thy * inv_l0, thz * inv_l0};
  const T radius = c.radius_ratio * min(in.r1, in.r2);
  const T area = std::numbers::pi * radius * radius;
  const T second_moment = std::numbers::pi * radius * radius * radius * radius / 4;
  const double E = c.youngs, G = c.shear;
  const double shear_factor = c.shear_coefficient * G;

  // Effects: the bond's strength and damage from its state; the Maxwell arm advanced over the step
  // (MaxwellArm::advance); Gamma + h_Gamma and kappa + h_kappa are what the strength sees.
  T strength = c.strength;
  T damage = 0;
  T h[6] = {0, 0, 0, 0, 0, 0};
  T total_strain[3] = {strain[0], strain[1], strain[2]};
  T total_curvature[3] = {curvature[0], curvature[1], curvature[2]};
  if constexpr (effects) {
    strength = s[kStrengthSlot];
    damage = s[kDamageSlot];
  }
  if constexpr (arm) {
    constexpr std::size_t P = kPreviousStrainSlot, H = kArmStrainSlot;
    for (int k = 0; k < 3; ++k) {
      h[k] = c.arm_decay * s[H + k] + c.arm_gain * (strain[k] - s[P + k]);
      h[3 + k] = c.arm_decay * s[H + 3 + k] + c.arm_gain * (curvature[k] - s[P + 3 + k]);
      total_strain[k] = strain[k] + h[k];
      total_curvature[k] = curvature[k] + h[3 + k];
      out.next_arm[k] = strain[k];
      out.next_arm[3 + k] = curvature[k];
      out.next_arm[6 + k] = h[k];
      out.next_arm[9 + k] = h[3 + k];
    }
  }

  // Breakage: the bound first (no square root); at width 1 the decision where it may reach.
  Mask reach(false);
  if constexpr (breakage) {
    reach = may_reach(total_strain, total_curvature, E, G, radius, strength) ||
            extra.may_break(strain, curvature, radius, c);
  }
  if constexpr (full) {
    out.fallback = false;
    if (breakage && reach) {
      const BondStress st = stress_of(total_strain, total_curvature, E, G, radius);
      const bool extra_breaks = extra.breaks(strain, curvature, st, c);
      if (st.sigma_vm >= strength || extra_breaks) {
        const bool softens = effects && c.softening_ratio > 0 && !extra_breaks;
        if (softens) damage = std::max(damage, softening_damage(st.sigma_vm, strength, c.softening_ratio));
        if (!softens || damage >= 1) {
          out.broken = true;
          out.stress = st;
          return out;
        }
      }
    }
    out.damage = damage;
  } else {
    Mask fallback = !unit || !series || reach;
    if constexpr (effects) fallback = fallback || damage != 0;
    out.fallback = fallback;
  }

  // Eq. 3 and 5 (with effects: the compressive axial modulus), the energy.
  T axial_factor = E;
  if constexpr (effects) axial_factor = axial_modulus(strain[0], T(E), T(c.compression_modulus));
  T F[3] = {axial_factor * area * strain[0], shear_factor * area * strain[1], shear_factor * area * strain[2]};
  T M[3] = {(2 * G) * second_moment * curvature[0], E * second_moment * curvature[1],
            E * second_moment * curvature[2]};
  T energy = 0.5 * l0 * (((strain[0] * F[0] + strain[1] * F[1]) + strain[2] * F[2]) +
                         ((curvature[0] * M[0] + curvature[1] * M[1]) + curvature[2] * M[2]));
  if constexpr (arm) {
    // The arm's stress: each component's elastic modulus (E_b axial and bending, G_b shear and
    // twist, as in tension); its spring holds the energy E_b h^2 / (2 beta).
    const T aF[3] = {E * area * h[0], shear_factor * area * h[1], shear_factor * area * h[2]};
    const T aM[3] = {(2 * G) * second_moment * h[3], E * second_moment * h[4], E * second_moment * h[5]};
    for (int k = 0; k < 3; ++k) {
      F[k] = F[k] + aF[k];
      M[k] = M[k] + aM[k];
    }
    energy = energy + 0.5 * l0 * (((h[0] * aF[0] + h[1] * aF[1]) + h[2] * aF[2]) +
                                  ((h[3] * aM[0] + h[4] * aM[1]) + h[5] * aM[2])) /
                          c.arm_modulus_ratio;
  }
  if constexpr (full && effects) {
    if (damage > 0) {  // softening: the secant (1 - D) on everything elastic
      const double intact = 1 - damage;
      for (int k = 0; k < 3; ++k) {
        F[k] *= intact;
        M[k] *= intact;
      }
      energy *= intact;
    }
  }
  out.energy = energy;

  // Rates conjugate to Gamma and kappa: omega_rel = M Bm^T (w2 - w1) and (eq. 4) v12 = l0 dGamma/dt.
  T o1[3], o2[3];
  to_bond(in.w1[0], in.w1[1], in.w1[2], o1);
  to_bond(in.w2[0], in.w2[1], in.w2[2], o2);
  const T ux = o2[0] - o1[0], uy = o2[1] - o1[1], uz = o2[2] - o1[2];
  const T vu = mu_axis * ((vx * ux + vy * uy) + vz * uz);
  const T orx = mu * ux + vu * vx, ory = mu * uy + vu * vy, orz = mu * uz + vu * vz;
  if constexpr (viscous) {
    const T ax = o1[0] - o2[0], ay = o1[1] - o2[1], az = o1[2] - o2[2];
    const T fsx = 0.5 * (o1[0] + o2[0]) + (sky * az - skz * ay);
    const T fsy = 0.5 * (o1[1] + o2[1]) + (skz * ax - skx * az);
    const T fsz = 0.5 * (o1[2] + o2[2]) + (skx * ay - sky * ax);
    T rv[3];
    to_bond(in.v2[0] - in.v1[0], in.v2[1] - in.v1[1], in.v2[2] - in.v1[2], rv);
    F[0] = F[0] + c.damping * (rv[0] - (fsy * dl[2] - fsz * dl[1]));
    F[1] = F[1] + c.damping * (rv[1] - (fsz * dl[0] - fsx * dl[2]));
    F[2] = F[2] + c.damping * (rv[2] - (fsx * dl[1] - fsy * dl[0]));
  }

  // Eq. 6-7: c_bend = f sqrt(E) sqrt(J I_r / l0), c_twist = c_bend sqrt(2 G / E).
  const T inertia_r = in.i1 * in.i2 / (in.i1 + in.i2);
  const T c_bend = c.bend_scale * sqrt(second_moment * inertia_r * inv_l0);
  const T c_twist = c_bend * c.twist_over_bend;
  const T ttx = M[0] + c_twist * orx, tty = M[1] + c_bend * ory, ttz = M[2] + c_bend * orz;

  // Loads on the ends: the couple C = d x F split half and half plus the skew part, and M T.
  const T cpx = dl[1] * F[2] - dl[2] * F[1], cpy = dl[2] * F[0] - dl[0] * F[2], cpz = dl[0] * F[1] - dl[1] * F[0];
  const T csx = sky * cpz - skz * cpy, csy = skz * cpx - skx * cpz, csz = skx * cpy - sky * cpx;
  const T vt = mu_axis * ((vx * ttx + vy * tty) + vz * ttz);
  const T btx = mu * ttx + vt * vx, bty = mu * tty + vt * vy, btz = mu * ttz + vt * vz;
  to_lab(F[0], F[1], F[2], out.force);
  to_lab((0.5 * cpx - csx) + btx, (0.5 * cpy - csy) + bty, (0.5 * cpz - csz) + btz, out.torque_first);
  to_lab((0.5 * cpx + csx) - btx, (0.5 * cpy + csy) - bty, (0.5 * cpz + csz) - btz, out.torque_second);
  return out;
}

}  // namespace shard::beam
