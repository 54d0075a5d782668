#include "beam_batch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "beam_geometry.hpp"
#include "effects/bond_effects.hpp"
#include "effects/compression_asymmetry.hpp"

namespace shard::beam {
namespace {

// Eigen 3.4's SSE product of double quaternions (Geometry/arch/Geometry_SIMD.h), term for term:
// its grouping differs from the textbook formula, and the lanes must round as it does.
struct Q {
  double w, x, y, z;
};

[[gnu::always_inline]] inline Q product(const Q& a, const Q& b) {
  return {(a.w * b.w - a.y * b.y) - (a.z * b.z + a.x * b.x), (a.w * b.x + a.y * b.z) - (a.z * b.y - a.x * b.w),
          (a.w * b.y + a.y * b.w) + (a.z * b.x - a.x * b.z), (a.w * b.z - a.y * b.x) + (a.z * b.w + a.x * b.y)};
}

// One loop body without branches (the rare cases only set `fallback`; breakage, the viscous
// force and the effects are template arguments because GCC does not unswitch a loop this large),
// so it vectorises. With `effects` the four policies of effects/bond_effects.hpp are composed in,
// in the per-bond path's order (BeamBond::compute_bond<true>): the bond's own strength, the
// Maxwell arm advanced over the step (in the breakage bound, the force, the torque and the
// energy), the compressive axial modulus; a damaged bond (softening) falls back.
// The particle fields are read straight through the lane's indices (gathers where the ISA has
// them): copying them into lane arrays first cost more than the arithmetic.
template <bool breakage, bool viscous, bool effects, bool arm>
[[gnu::always_inline]] inline void evaluate_lanes(const BlockInput& in, BlockOutput& out, std::size_t n,
                                                  const BlockConstants& c) {
  const Index* __restrict first = in.first;
  const Index* __restrict second = in.second;
  const std::int64_t* __restrict swapped = in.swapped;
  double* __restrict force = out.force;
  double* __restrict torque_i = out.torque_i;
  double* __restrict torque_j = out.torque_j;
  double* __restrict energy = out.energy;
  // The state's stride of 9 (11, 23) defeats GCC's interleaved loads: transposed into lanes first.
  constexpr std::size_t stride = !effects ? kStateSize : arm ? kViscousStateSize : kEffectsStateSize;
  alignas(64) double st[stride][kBlockLanes];
  for (std::size_t l = 0; l < n; ++l)
    for (std::size_t k = 0; k < stride; ++k) st[k][l] = in.state[l * stride + k];
  const double* __restrict x = in.position;
  const double* __restrict v = in.velocity;
  const double* __restrict q = in.orientation;
  const double* __restrict omega = in.omega;
  const double* __restrict radius_of = in.radius;
  const double* __restrict inertia = in.inertia;
  const double E = c.youngs, G = c.shear;
  const double axial_stiffness_factor = E;
  const double shear_factor = c.shear_coefficient * G;
  const double twist_factor = 2 * G;
  const double strength_bound = (1 - 1e-12) * c.strength * c.strength;
#pragma GCC ivdep
  for (std::size_t l = 0; l < n; ++l) {
    const std::size_t a = static_cast<std::size_t>(first[l]), b = static_cast<std::size_t>(second[l]);
    const double s[kStateSize] = {st[0][l], st[1][l], st[2][l], st[3][l], st[4][l],
                                  st[5][l], st[6][l], st[7][l], st[8][l]};
    // deform(): frames of the two ends, relative rotation, its normalisation.
    const Q f1 = product({q[4 * a + 3], q[4 * a], q[4 * a + 1], q[4 * a + 2]}, {s[1], s[2], s[3], s[4]});
    const Q f2 = product({q[4 * b + 3], q[4 * b], q[4 * b + 1], q[4 * b + 2]}, {s[5], s[6], s[7], s[8]});
    Q rel = product({f1.w, -f1.x, -f1.y, -f1.z}, f2);
    const double norm2 = (rel.x * rel.x + rel.z * rel.z) + (rel.y * rel.y + rel.w * rel.w);
    const double e = norm2 - 1;
    const bool unit = std::abs(e) < 1e-9;
    const double scale = std::copysign(1 - 0.5 * e, rel.w);
    rel = {rel.w * scale, rel.x * scale, rel.y * scale, rel.z * scale};
    const double vx = rel.x, vy = rel.y, vz = rel.z, w = rel.w;
    const double s2 = (vx * vx + vy * vy) + vz * vz;
    const bool series = s2 < kSeriesLimit;
    const double tail = arcsin_ratio_tail(s2);
    const double mu = 1 + s2 * tail;
    const double mu_axis = -tail;
    const double two_mu = 2 * mu;
    const double thx = two_mu * vx, thy = two_mu * vy, thz = two_mu * vz;
    const double one_w = 1 + w;
    const double inv_root = 1 / std::sqrt(2 * one_w);
    const double k2 = inv_root * inv_root;
    const double skx = k2 * vx, sky = k2 * vy, skz = k2 * vz;
    const Q m = product(f1, {inv_root * one_w, inv_root * vx, inv_root * vy, inv_root * vz});
    // toRotationMatrix()
    const double tx = 2 * m.x, ty = 2 * m.y, tz = 2 * m.z;
    const double twx = tx * m.w, twy = ty * m.w, twz = tz * m.w;
    const double txx = tx * m.x, txy = ty * m.x, txz = tz * m.x;
    const double tyy = ty * m.y, tyz = tz * m.y, tzz = tz * m.z;
    const double R00 = 1 - (tyy + tzz), R01 = txy - twz, R02 = txz + twy;
    const double R10 = txy + twz, R11 = 1 - (txx + tzz), R12 = tyz - twx;
    const double R20 = txz - twy, R21 = tyz + twx, R22 = 1 - (txx + tyy);
    const double dx = x[3 * b] - x[3 * a], dy = x[3 * b + 1] - x[3 * a + 1], dz = x[3 * b + 2] - x[3 * a + 2];
    const double dlx = (R00 * dx + R10 * dy) + R20 * dz;
    const double dly = (R01 * dx + R11 * dy) + R21 * dz;
    const double dlz = (R02 * dx + R12 * dy) + R22 * dz;

    // strain_curvature(), section_of()
    const double l0 = s[0];
    const double inv_l0 = 1 / l0;
    const double sx = dlx * inv_l0 - 1, sy = dly * inv_l0, sz = dlz * inv_l0;
    const double cx = thx * inv_l0, cy = thy * inv_l0, cz = thz * inv_l0;
    const double radius = c.radius_ratio * std::min(radius_of[a], radius_of[b]);
    const double area = std::numbers::pi * radius * radius;
    const double second_moment = std::numbers::pi * radius * radius * radius * radius / 4;

    // Effects: the bond's strength and damage from its state; with the arm, its strains h advanced
    // over the step (MaxwellArm::advance).
    double bound = strength_bound;
    bool damaged = false;
    double hsx = 0, hsy = 0, hsz = 0, hcx = 0, hcy = 0, hcz = 0;
    double tsx = sx, tsy = sy, tsz = sz, tcx = cx, tcy = cy, tcz = cz;  // Gamma + h_Gamma, kappa + h_kappa
    if constexpr (effects) {
      const double strength = st[kStrengthSlot][l];
      bound = (1 - 1e-12) * strength * strength;
      damaged = st[kDamageSlot][l] != 0;
    }
    if constexpr (arm) {
      constexpr std::size_t P = kPreviousStrainSlot, H = kArmStrainSlot;
      hsx = c.arm_decay * st[H][l] + c.arm_gain * (sx - st[P][l]);
      hsy = c.arm_decay * st[H + 1][l] + c.arm_gain * (sy - st[P + 1][l]);
      hsz = c.arm_decay * st[H + 2][l] + c.arm_gain * (sz - st[P + 2][l]);
      hcx = c.arm_decay * st[H + 3][l] + c.arm_gain * (cx - st[P + 3][l]);
      hcy = c.arm_decay * st[H + 4][l] + c.arm_gain * (cy - st[P + 4][l]);
      hcz = c.arm_decay * st[H + 5][l] + c.arm_gain * (cz - st[P + 5][l]);
      tsx = sx + hsx, tsy = sy + hsy, tsz = sz + hsz, tcx = cx + hcx, tcy = cy + hcy, tcz = cz + hcz;
    }

    // may_reach()
    bool reach = false;
    if constexpr (breakage) {
      const double axial = std::max(E * tsx, 0.0) + E * radius * (std::abs(tcy) + std::abs(tcz));
      const double tau = G * (std::abs(tsy) + std::abs(tsz)) + G * radius * std::abs(tcx);
      reach = axial * axial + 3 * tau * tau >= bound;
    }
    const bool fallback = !unit | !series | reach | damaged;
    out.fallback[l] = static_cast<std::int64_t>(fallback);
    if constexpr (arm) {  // a selection, so the store needs no branch; a fallback lane keeps its state
      const double next[12] = {sx, sy, sz, cx, cy, cz, hsx, hsy, hsz, hcx, hcy, hcz};
      double* __restrict slots = out.state + l * kViscousStateSize + kPreviousStrainSlot;
      for (std::size_t k = 0; k < 12; ++k) slots[k] = fallback ? st[kPreviousStrainSlot + k][l] : next[k];
    }

    // Eq. 3 and 5 (with effects: the compressive axial modulus), energy.
    double axial_factor = axial_stiffness_factor;
    if constexpr (effects) axial_factor = axial_modulus(sx, E, c.compression_modulus);
    double Fx = axial_factor * area * sx, Fy = shear_factor * area * sy, Fz = shear_factor * area * sz;
    double Tx = twist_factor * second_moment * cx, Ty = E * second_moment * cy, Tz = E * second_moment * cz;
    double lane_energy = 0.5 * l0 * (((sx * Fx + sy * Fy) + sz * Fz) + ((cx * Tx + cy * Ty) + cz * Tz));
    if constexpr (arm) {
      // The arm's stress: each component's elastic modulus (E_b axial and bending, G_b shear and
      // twist, as in tension); its spring holds the energy E_b h^2 / (2 beta).
      const double aFx = E * area * hsx, aFy = shear_factor * area * hsy, aFz = shear_factor * area * hsz;
      const double aTx = twist_factor * second_moment * hcx, aTy = E * second_moment * hcy,
                   aTz = E * second_moment * hcz;
      Fx = Fx + aFx, Fy = Fy + aFy, Fz = Fz + aFz;
      Tx = Tx + aTx, Ty = Ty + aTy, Tz = Tz + aTz;
      lane_energy = lane_energy + 0.5 * l0 * (((hsx * aFx + hsy * aFy) + hsz * aFz) + ((hcx * aTx + hcy * aTy) + hcz * aTz)) /
                                      c.arm_modulus_ratio;
    }
    energy[l] = lane_energy;

    // rates_of()
    const double o1x = omega[3 * a], o1y = omega[3 * a + 1], o1z = omega[3 * a + 2];
    const double o2x = omega[3 * b], o2y = omega[3 * b + 1], o2z = omega[3 * b + 2];
    const double w1x = (R00 * o1x + R10 * o1y) + R20 * o1z;
    const double w1y = (R01 * o1x + R11 * o1y) + R21 * o1z;
    const double w1z = (R02 * o1x + R12 * o1y) + R22 * o1z;
    const double w2x = (R00 * o2x + R10 * o2y) + R20 * o2z;
    const double w2y = (R01 * o2x + R11 * o2y) + R21 * o2z;
    const double w2z = (R02 * o2x + R12 * o2y) + R22 * o2z;
    const double ux = w2x - w1x, uy = w2y - w1y, uz = w2z - w1z;
    const double vu = mu_axis * ((vx * ux + vy * uy) + vz * uz);
    const double orx = mu * ux + vu * vx, ory = mu * uy + vu * vy, orz = mu * uz + vu * vz;
    if constexpr (viscous) {
      const double ax = w1x - w2x, ay = w1y - w2y, az = w1z - w2z;
      const double fsx = 0.5 * (w1x + w2x) + (sky * az - skz * ay);
      const double fsy = 0.5 * (w1y + w2y) + (skz * ax - skx * az);
      const double fsz = 0.5 * (w1z + w2z) + (skx * ay - sky * ax);
      const double dvx = v[3 * b] - v[3 * a], dvy = v[3 * b + 1] - v[3 * a + 1], dvz = v[3 * b + 2] - v[3 * a + 2];
      const double rvx = (R00 * dvx + R10 * dvy) + R20 * dvz;
      const double rvy = (R01 * dvx + R11 * dvy) + R21 * dvz;
      const double rvz = (R02 * dvx + R12 * dvy) + R22 * dvz;
      const double v12x = rvx - (fsy * dlz - fsz * dly);
      const double v12y = rvy - (fsz * dlx - fsx * dlz);
      const double v12z = rvz - (fsx * dly - fsy * dlx);
      Fx = Fx + c.damping * v12x;
      Fy = Fy + c.damping * v12y;
      Fz = Fz + c.damping * v12z;
    }

    // RotationalDamping::torque()
    const double i1 = inertia[a], i2 = inertia[b];
    const double inertia_r = i1 * i2 / (i1 + i2);
    const double c_bend = c.bend_scale * std::sqrt(second_moment * inertia_r * inv_l0);
    const double c_twist = c_bend * c.twist_over_bend;
    const double ttx = Tx + c_twist * orx, tty = Ty + c_bend * ory, ttz = Tz + c_bend * orz;

    // pair_loads(). Eigen's R * u: rows 0 and 1 as one packet, (a0 + a1) + a2; row 2 by its
    // scalar unroller, which halves the sum: a0 + (a1 + a2).
    const double cpx = dly * Fz - dlz * Fy, cpy = dlz * Fx - dlx * Fz, cpz = dlx * Fy - dly * Fx;
    const double csx = sky * cpz - skz * cpy, csy = skz * cpx - skx * cpz, csz = skx * cpy - sky * cpx;
    const double vt = mu_axis * ((vx * ttx + vy * tty) + vz * ttz);
    const double btx = mu * ttx + vt * vx, bty = mu * tty + vt * vy, btz = mu * ttz + vt * vz;
    const double ffx = (R00 * Fx + R01 * Fy) + R02 * Fz;
    const double ffy = (R10 * Fx + R11 * Fy) + R12 * Fz;
    const double ffz = R20 * Fx + (R21 * Fy + R22 * Fz);
    const double ax = (0.5 * cpx - csx) + btx, ay = (0.5 * cpy - csy) + bty, az = (0.5 * cpz - csz) + btz;
    const double bx = (0.5 * cpx + csx) - btx, by = (0.5 * cpy + csy) - bty, bz = (0.5 * cpz + csz) - btz;
    const double tax = (R00 * ax + R01 * ay) + R02 * az;
    const double tay = (R10 * ax + R11 * ay) + R12 * az;
    const double taz = R20 * ax + (R21 * ay + R22 * az);
    const double tbx = (R00 * bx + R01 * by) + R02 * bz;
    const double tby = (R10 * bx + R11 * by) + R12 * bz;
    const double tbz = R20 * bx + (R21 * by + R22 * bz);
    // A selection, not a branch: which end the batch lists first is close to random.
    const bool sw = swapped[l] != 0;
    force[3 * l] = sw ? -ffx : ffx;
    force[3 * l + 1] = sw ? -ffy : ffy;
    force[3 * l + 2] = sw ? -ffz : ffz;
    torque_i[3 * l] = sw ? tbx : tax;
    torque_i[3 * l + 1] = sw ? tby : tay;
    torque_i[3 * l + 2] = sw ? tbz : taz;
    torque_j[3 * l] = sw ? tax : tbx;
    torque_j[3 * l + 1] = sw ? tay : tby;
    torque_j[3 * l + 2] = sw ? taz : tbz;
  }
}

template <bool effects, bool arm>
[[gnu::always_inline]] inline void evaluate_law(const BlockInput& in, BlockOutput& out, std::size_t n,
                                                const BlockConstants& c) {
  if (c.breakage) {
    if (c.viscous_force) evaluate_lanes<true, true, effects, arm>(in, out, n, c);
    else evaluate_lanes<true, false, effects, arm>(in, out, n, c);
  } else {
    if (c.viscous_force) evaluate_lanes<false, true, effects, arm>(in, out, n, c);
    else evaluate_lanes<false, false, effects, arm>(in, out, n, c);
  }
}

[[gnu::always_inline]] inline void evaluate_any(const BlockInput& in, BlockOutput& out, std::size_t n,
                                                const BlockConstants& c) {
  if (!c.effects) evaluate_law<false, false>(in, out, n, c);
  else if (c.arm) evaluate_law<true, true>(in, out, n, c);
  else evaluate_law<true, false>(in, out, n, c);
}

void evaluate_baseline(const BlockInput& in, BlockOutput& out, std::size_t n, const BlockConstants& c) {
  evaluate_any(in, out, n, c);
}

// AVX2 and AVX-512 run 4 and 8 lanes of the same IEEE operations; beam_batch.cpp is compiled with
// -ffp-contract=off, so neither fuses a multiply-add and each rounds exactly as the x86-64-v2
// per-bond path does (the AVX-512 target would otherwise use FMA). Chosen at run time by a plain
// CPU test rather than an ifunc, which may run before the sanitizer runtime is initialised.
#if defined(__x86_64__)
[[gnu::target("avx2")]] void evaluate_avx2(const BlockInput& in, BlockOutput& out, std::size_t n,
                                           const BlockConstants& c) {
  evaluate_any(in, out, n, c);
}

[[gnu::target("avx512f")]] void evaluate_avx512(const BlockInput& in, BlockOutput& out, std::size_t n,
                                                const BlockConstants& c) {
  evaluate_any(in, out, n, c);
}
#endif

}  // namespace

const char* name_of(BlockIsa isa) {
  switch (isa) {
    case BlockIsa::Avx512: return "avx512f";
    case BlockIsa::Avx2: return "avx2";
    case BlockIsa::Baseline: break;
  }
  return "x86-64-v2";
}

bool runs_here(BlockIsa isa) {
#if defined(__x86_64__)
  switch (isa) {
    case BlockIsa::Avx512: return __builtin_cpu_supports("avx512f");
    case BlockIsa::Avx2: return __builtin_cpu_supports("avx2");
    case BlockIsa::Baseline: break;
  }
#endif
  return isa == BlockIsa::Baseline;
}

BlockFunction block_function(BlockIsa isa) {
  switch (isa) {
#if defined(__x86_64__)
    case BlockIsa::Avx512: return evaluate_avx512;
    case BlockIsa::Avx2: return evaluate_avx2;
#endif
    default: return evaluate_baseline;
  }
}

BlockIsa widest_block_isa() {
  for (const BlockIsa isa : {BlockIsa::Avx512, BlockIsa::Avx2})
    if (runs_here(isa)) return isa;
  return BlockIsa::Baseline;
}

}  // namespace shard::beam
