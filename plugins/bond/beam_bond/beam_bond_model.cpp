#include "beam_bond_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "beam_batch.hpp"
#include "beam_geometry.hpp"
#include "bond_step.hpp"
#include "beam_stress.hpp"
#include "effects/cohesive_softening.hpp"
#include "effects/compression_asymmetry.hpp"
#include "effects/maxwell_arm.hpp"
#include "effects/weibull_strength.hpp"

namespace shard::beam {

BeamBondParams BeamBondParams::from(const ParamSet& p) {
  BeamBondParams b;
  b.youngs_modulus = p.number("youngs_modulus");
  b.shear_modulus = p.number("shear_modulus");
  b.poisson_ratio = p.number("poisson_ratio");
  b.shear_coefficient = p.number("shear_coefficient");
  b.radius_ratio = p.number("radius_ratio");
  b.damping = p.number("damping");
  b.rotational_damping = p.number("rotational_damping");
  b.critical_stress = p.number("critical_stress");
  b.breakage = p.flag("breakage");
  b.effects = BondEffects::from(p);
  return b;
}

BeamBond::BeamBond(const BeamBondParams& params, BlockIsa isa)
    : p_(params),
      shear_modulus_(params.effective_shear_modulus()),
      rotational_(params.rotational_damping, params.youngs_modulus, shear_modulus_),
      block_step_(block_function(isa)) {
  if (!runs_here(isa))
    throw std::invalid_argument(std::string("beam_bond: this CPU cannot run the ") + name_of(isa) + " block step");
  block_.youngs = p_.youngs_modulus;
  block_.shear = shear_modulus_;
  block_.shear_coefficient = p_.shear_coefficient;
  block_.radius_ratio = p_.radius_ratio;
  block_.damping = p_.damping;
  block_.strength = p_.critical_stress;
  block_.bend_scale = rotational_.bend_scale();
  block_.twist_over_bend = rotational_.twist_over_bend();
  block_.breakage = p_.breakage;
  block_.viscous_force = p_.damping != 0;
  if (!(p_.youngs_modulus > 0) || !(shear_modulus_ > 0) || !(p_.shear_coefficient > 0) || !(p_.radius_ratio > 0))
    throw std::invalid_argument("beam_bond: youngs_modulus, shear modulus, shear_coefficient and radius_ratio must be > 0");
  const BondEffects& fx = p_.effects;
  if (!(fx.strength_weibull_modulus >= 0) || !(fx.softening_ratio >= 0) || !(fx.viscosity_time >= 0))
    throw std::invalid_argument("beam_bond: strength_weibull_modulus, softening_ratio, viscosity_time must be >= 0");
  if (!(fx.viscous_modulus_ratio > 0) || !(fx.compression_stiffness_ratio > 0))
    throw std::invalid_argument("beam_bond: viscous_modulus_ratio and compression_stiffness_ratio must be > 0");
  block_.effects = fx.any();
  block_.arm = block_.effects && fx.viscous();
  block_.compression_modulus = fx.compression_stiffness_ratio * p_.youngs_modulus;
  block_.arm_modulus_ratio = fx.viscous_modulus_ratio;
  if (fx.strength_weibull_modulus > 0)
    weibull_scale_ = weibull_scale(p_.critical_stress, fx.strength_weibull_modulus);
}

std::size_t BeamBond::state_size() const {
  return !block_.effects ? kStateSize : block_.arm ? kViscousStateSize : kEffectsStateSize;
}

double BeamBond::strength_of(std::int64_t id_a, std::int64_t id_b) const {
  const BondEffects& fx = p_.effects;
  if (!(fx.strength_weibull_modulus > 0)) return p_.critical_stress;
  return weibull_quantile(bond_uniform(fx.strength_seed, id_a, id_b), weibull_scale_, fx.strength_weibull_modulus);
}

void BeamBond::initialize(BondBatch& batch) const {
  const ParticleView& p = batch.particles;
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Ends e = ends_of(p, batch.i[k], batch.j[k]);
    const Reference ref = reference_of(p.position[e.first], p.position[e.second], p.orientation[e.first],
                                       p.orientation[e.second]);
    if (!(ref.l0 > 0)) throw std::invalid_argument("beam_bond: a bond joins two particles at the same position");
    double* s = batch.state + k * state_size();
    store(s, ref);
    if (block_.effects) {
      const std::int64_t id1 = p.id ? p.id[e.first] : e.first;
      const std::int64_t id2 = p.id ? p.id[e.second] : e.second;
      s[kStrengthSlot] = strength_of(id1, id2);
      std::fill(s + kDamageSlot, s + state_size(), 0.0);  // intact (unstrained, arm relaxed)
    }
  }
}

// Eq. 12: t_bond = 0.17 sqrt(m / K), lightest bonded particle, stiffest bond K = E_b A_b / l0,
// with the stiffer of the tensile and compressive axial springs plus the Maxwell arm's beta E_b
// when viscosity is on (the most a step can see of it, maxwell_arm.hpp); eq. 4's dashpot against
// the softest axial spring (damped_step.hpp). At the neutral values both moduli are E_b.
TimeStepLimit BeamBond::time_step_limit(const BondBatch& batch) const {
  const BondEffects& fx = p_.effects;
  const double arm = fx.viscous() ? fx.viscous_modulus_ratio : 0.0;
  const double E = p_.youngs_modulus;
  const AxialModuli moduli{(std::max(1.0, fx.compression_stiffness_ratio) + arm) * E,
                           std::min(1.0, fx.compression_stiffness_ratio) * E};
  TimeStepLimit limit;
  limit.name = p_.damping > 0 ? "beam_bond t_bond (eq. 12, with eq. 4's damping)" : "beam_bond t_bond (eq. 12)";
  limit.critical = eq12_step(batch, state_size(), p_.radius_ratio, moduli, p_.damping);
  limit.recommended = limit.critical;
  return limit;
}

// The per-bond path: the reference the blocked path is checked against bit for bit, and what
// runs the lanes the blocked path leaves (near failure, large rotations, off-unit quaternions,
// damaged bonds). With `effects` the policies act in this order: the Maxwell arm advanced over the
// step (its strains join Gamma and kappa in the breakage check), the bond's own strength,
// softening instead of a break, the compressive axial modulus, the arm's force, torque and
// energy, the damage scaling all of them. Each is exact at its neutral value.
template <bool effects>
void BeamBond::compute_bond(BondBatch& batch, std::size_t k) const {
  const ParticleView& p = batch.particles;
  const double E = p_.youngs_modulus;
  const double G = shear_modulus_;
  const double a_s = p_.shear_coefficient;
  const bool viscous_force = block_.viscous_force;
  const BondEffects& fx = p_.effects;

  const Ends e = ends_of(p, batch.i[k], batch.j[k]);
  const Index n1 = e.first, n2 = e.second;
  double* state = batch.state + k * state_size();
  const Reference ref = load(state);
  const double l0 = ref.l0;
  const double inv_l0 = 1 / l0;
  const Section sec = section_of(p_.radius_ratio, p.radius[n1], p.radius[n2]);
  const Deformation g = deform(ref, p.position[n1], p.position[n2], p.orientation[n1], p.orientation[n2]);

  // Strain and curvature vectors, bond frame.
  const auto [strain, curvature] = strain_curvature(g, inv_l0);  // Gamma, kappa

  // The Maxwell arm (maxwell_arm.hpp) advanced over this step: the material stress follows
  // Gamma + h_Gamma (and likewise kappa), and so does the strength check.
  Vec3 arm_strain = Vec3::Zero(), arm_curvature = Vec3::Zero();
  Vec3 strain_total = strain, curvature_total = curvature;
  double strength = p_.critical_stress, damage = 0;
  if constexpr (effects) {
    strength = state[kStrengthSlot];
    damage = state[kDamageSlot];
    if (fx.viscous()) {
      const MaxwellArm arm(fx.viscosity_time, fx.viscous_modulus_ratio, batch.dt);
      double* previous = state + kPreviousStrainSlot;
      double* h = state + kArmStrainSlot;
      for (int c = 0; c < 3; ++c) {
        arm_strain[c] = arm.advance(h[c], strain[c] - previous[c]);
        arm_curvature[c] = arm.advance(h[3 + c], curvature[c] - previous[3 + c]);
        previous[c] = strain[c];
        previous[3 + c] = curvature[c];
        h[c] = arm_strain[c];
        h[3 + c] = arm_curvature[c];
      }
      strain_total += arm_strain;
      curvature_total += arm_curvature;
    }
  }

  if (p_.breakage && may_reach(strain_total, curvature_total, E, G, sec.radius, strength)) {
    const BondStress s = stress_of(strain_total, curvature_total, E, G, sec.radius);
    if (s.sigma_vm >= strength) {
      if (!effects || !(fx.softening_ratio > 0)) {
        write_broken(batch, k, s);
        return;
      }
      damage = std::max(damage, softening_damage(s.sigma_vm, strength, fx.softening_ratio));
      if (damage >= 1) {
        write_broken(batch, k, s);
        return;
      }
      state[kDamageSlot] = damage;
    }
  }

  // Eq. 3 and 5: elastic force and torque, bond frame (with effects: the compressive axial modulus).
  const double axial = effects ? axial_modulus(strain.x(), E, block_.compression_modulus) : E;
  Vec3 elastic_force(axial * sec.area * strain.x(), a_s * G * sec.area * strain.y(), a_s * G * sec.area * strain.z());
  Vec3 elastic_torque(2 * G * sec.second_moment * curvature.x(), E * sec.second_moment * curvature.y(),
                      E * sec.second_moment * curvature.z());
  double energy = 0.5 * l0 * (strain.dot(elastic_force) + curvature.dot(elastic_torque));
  if constexpr (effects) {
    if (fx.viscous()) {
      // The arm's stress on each component has that component's elastic modulus (E_b on the axial
      // and bending strains, G_b on shear and twist, as tensile bonds); its spring holds h / beta.
      const Vec3 arm_force(E * sec.area * arm_strain.x(), a_s * G * sec.area * arm_strain.y(),
                           a_s * G * sec.area * arm_strain.z());
      const Vec3 arm_torque(2 * G * sec.second_moment * arm_curvature.x(), E * sec.second_moment * arm_curvature.y(),
                            E * sec.second_moment * arm_curvature.z());
      elastic_force += arm_force;
      elastic_torque += arm_torque;
      energy += 0.5 * l0 * (arm_strain.dot(arm_force) + arm_curvature.dot(arm_torque)) / fx.viscous_modulus_ratio;
    }
    if (damage > 0) {
      const double intact = 1 - damage;
      elastic_force *= intact;
      elastic_torque *= intact;
      energy *= intact;
    }
  }
  batch.energy[k] = energy;

  // Eq. 4: viscous force on the objective strain rate v12 = l0 dGamma/dt; eq. 6-7: viscous torque
  // on Omega_rel = d theta / dt. Both zero for rigid motion; numerical damping, not an effect.
  const Rates r = rates_of(g, p.velocity[n1], p.velocity[n2], p.omega[n1], p.omega[n2], viscous_force);
  Vec3 force = elastic_force;
  if (viscous_force) force += p_.damping * r.v12;
  const Vec3 damping_torque = rotational_.torque(sec.second_moment, inv_l0, p.inertia[n1], p.inertia[n2], r.omega_rel);

  const PairLoads loads = pair_loads(g, force, elastic_torque + damping_torque, e.swapped);
  batch.force[k] = loads.force_on_i;
  batch.torque_i[k] = loads.torque_on_i;
  batch.torque_j[k] = loads.torque_on_j;
}

void BeamBond::compute_one(BondBatch& batch, std::size_t k) const {
  if (block_.effects) compute_bond<true>(batch, k);
  else compute_bond<false>(batch, k);
}

void BeamBond::compute_reference(BondBatch& batch) const {
  for (std::size_t k = 0; k < batch.count; ++k) compute_one(batch, k);
}

// Gather a block into lanes, evaluate it in one vectorised loop, scatter; the lanes the loop
// leaves go through the per-bond path.
void BeamBond::compute(BondBatch& batch) const {
  const ParticleView& p = batch.particles;
  const std::size_t stride = state_size();
  const bool arm = block_.arm;
  BlockConstants constants = block_;
  if (arm) {  // the arm's factors depend on this batch's step
    const MaxwellArm step_arm(p_.effects.viscosity_time, p_.effects.viscous_modulus_ratio, batch.dt);
    constants.arm_decay = step_arm.decay;
    constants.arm_gain = step_arm.gain;
  }

  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Quat) == 4 * sizeof(double));
  BlockOutput out;
  Index first[kBlockLanes], second[kBlockLanes];
  std::int64_t swapped[kBlockLanes];
  BlockInput in;
  in.first = first;
  in.second = second;
  in.swapped = swapped;
  in.position = reinterpret_cast<const double*>(p.position);
  in.velocity = reinterpret_cast<const double*>(p.velocity);
  in.orientation = reinterpret_cast<const double*>(p.orientation);
  in.omega = reinterpret_cast<const double*>(p.omega);
  in.radius = p.radius;
  in.inertia = p.inertia;
  for (std::size_t base = 0; base < batch.count; base += kBlockLanes) {
    const std::size_t n = std::min(kBlockLanes, batch.count - base);
    for (std::size_t l = 0; l < n; ++l) {
      const Ends e = ends_of(p, batch.i[base + l], batch.j[base + l]);
      first[l] = e.first;
      second[l] = e.second;
      swapped[l] = e.swapped;
    }
    in.state = batch.state + base * stride;
    out.state = batch.state + base * stride;
    out.force = batch.force[base].data();
    out.torque_i = batch.torque_i[base].data();
    out.torque_j = batch.torque_j[base].data();
    out.energy = batch.energy + base;
    block_step_(in, out, n, constants);
    for (std::size_t l = 0; l < n; ++l)
      if (out.fallback[l]) compute_one(batch, base + l);
  }
}

}  // namespace shard::beam
