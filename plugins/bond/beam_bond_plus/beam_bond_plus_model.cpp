#include "beam_bond_plus_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "beam_geometry.hpp"
#include "beam_stress.hpp"
#include "cohesive_softening.hpp"
#include "bond_step.hpp"
#include "maxwell_arm.hpp"
#include "weibull_strength.hpp"

namespace shard::beam_plus {

using beam::Ends;
using beam::ends_of;
using beam::Section;
using beam::section_of;

BeamBondPlusParams BeamBondPlusParams::from(const ParamSet& p) {
  BeamBondPlusParams b;
  b.base = beam::BeamBondParams::from(p);
  b.strength_weibull_modulus = p.number("strength_weibull_modulus");
  b.strength_seed = static_cast<std::uint64_t>(p.integer("strength_seed"));
  b.softening_ratio = p.number("softening_ratio");
  b.viscosity_time = p.number("viscosity_time");
  b.viscous_modulus_ratio = p.number("viscous_modulus_ratio");
  b.compression_stiffness_ratio = p.number("compression_stiffness_ratio");
  return b;
}

BeamBondPlus::BeamBondPlus(const BeamBondPlusParams& params)
    : p_(params),
      shear_modulus_(params.base.effective_shear_modulus()),
      compression_modulus_(params.compression_stiffness_ratio * params.base.youngs_modulus),
      weibull_scale_(params.strength_weibull_modulus > 0
                         ? weibull_scale(params.base.critical_stress, params.strength_weibull_modulus)
                         : 0) {
  const auto& b = p_.base;
  if (!(b.youngs_modulus > 0) || !(shear_modulus_ > 0) || !(b.shear_coefficient > 0) || !(b.radius_ratio > 0))
    throw std::invalid_argument(
        "beam_bond_plus: youngs_modulus, shear modulus, shear_coefficient and radius_ratio must be > 0");
  if (!(p_.strength_weibull_modulus >= 0) || !(p_.softening_ratio >= 0) || !(p_.viscosity_time >= 0))
    throw std::invalid_argument("beam_bond_plus: strength_weibull_modulus, softening_ratio, viscosity_time must be >= 0");
  if (!(p_.viscous_modulus_ratio > 0)) throw std::invalid_argument("beam_bond_plus: viscous_modulus_ratio must be > 0");
  if (!(p_.compression_stiffness_ratio > 0))
    throw std::invalid_argument("beam_bond_plus: compression_stiffness_ratio must be > 0");
}

double BeamBondPlus::strength_of(std::int64_t id_a, std::int64_t id_b) const {
  if (!(p_.strength_weibull_modulus > 0)) return p_.base.critical_stress;
  return weibull_quantile(bond_uniform(p_.strength_seed, id_a, id_b), weibull_scale_, p_.strength_weibull_modulus);
}

void BeamBondPlus::initialize(BondBatch& batch) const {
  const ParticleView& p = batch.particles;
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Ends e = ends_of(p, batch.i[k], batch.j[k]);
    const beam::Reference ref = beam::reference_of(p.position[e.first], p.position[e.second],
                                                   p.orientation[e.first], p.orientation[e.second]);
    if (!(ref.l0 > 0)) throw std::invalid_argument("beam_bond_plus: a bond joins two particles at the same position");
    double* s = batch.state + k * state_size();
    beam::store(s, ref);
    const std::int64_t id1 = p.id ? p.id[e.first] : e.first;
    const std::int64_t id2 = p.id ? p.id[e.second] : e.second;
    s[kStrengthSlot] = strength_of(id1, id2);
    s[kDamageSlot] = 0;
    if (viscous()) std::fill(s + kPreviousStrainSlot, s + kViscousStateSize, 0.0);  // unstrained, arm relaxed
  }
}

// Eq. 12 with the stiffer of the tensile and compressive axial springs, plus the Maxwell arm's
// beta E_b when viscosity is on (the most a step can see of it, maxwell_arm.hpp).
TimeStepLimit BeamBondPlus::time_step_limit(const BondBatch& batch) const {
  const double arm = viscous() ? p_.viscous_modulus_ratio : 0.0;
  const double E = p_.base.youngs_modulus;
  // eq. 4's dashpot against the softest axial spring (damped_step.hpp).
  const beam::AxialModuli moduli{(std::max(1.0, p_.compression_stiffness_ratio) + arm) * E,
                                 std::min(1.0, p_.compression_stiffness_ratio) * E};
  TimeStepLimit limit;
  limit.name = "beam_bond_plus t_bond (eq. 12)";
  limit.critical = beam::eq12_step(batch, state_size(), p_.base.radius_ratio, moduli, p_.base.damping);
  limit.recommended = limit.critical;
  return limit;
}

void BeamBondPlus::compute(BondBatch& batch) const {
  const ParticleView& p = batch.particles;
  const beam::BeamBondParams& b = p_.base;
  const double E = b.youngs_modulus;
  const double G = shear_modulus_;
  const double a_s = b.shear_coefficient;
  const bool viscous = this->viscous();
  const MaxwellArm arm(p_.viscosity_time, p_.viscous_modulus_ratio, batch.dt);
  const std::size_t stride = state_size();
  const beam::RotationalDamping rotational(b.rotational_damping, E, G);

  for (std::size_t k = 0; k < batch.count; ++k) {
    const Ends e = ends_of(p, batch.i[k], batch.j[k]);
    const Index n1 = e.first, n2 = e.second;
    double* state = batch.state + k * stride;
    const beam::Reference ref = beam::load(state);
    const double l0 = ref.l0;
    const double inv_l0 = 1 / l0;
    const Section sec = section_of(b.radius_ratio, p.radius[n1], p.radius[n2]);
    const beam::Deformation g =
        beam::deform(ref, p.position[n1], p.position[n2], p.orientation[n1], p.orientation[n2]);

    const auto [strain, curvature] = beam::strain_curvature(g, inv_l0);  // Gamma, kappa

    // Rates conjugate to Gamma and kappa (beam_geometry.hpp): v12 = l0 dGamma/dt,
    // omega_rel = d theta/dt = l0 dkappa/dt. Zero for rigid motion of the pair.
    // Only eq. 4's damping reads v12 (the Maxwell arm works on strain increments).
    const beam::Rates r = beam::rates_of(g, p.velocity[n1], p.velocity[n2], p.omega[n1], p.omega[n2], b.damping != 0);
    const Vec3& v12 = r.v12;
    const Vec3& omega_rel = r.omega_rel;

    // The Maxwell arm (maxwell_arm.hpp) advanced over this step: the material stress follows
    // Gamma + h_Gamma (and likewise kappa), and so does the strength check.
    Vec3 arm_strain = Vec3::Zero(), arm_curvature = Vec3::Zero();
    Vec3 strain_total = strain, curvature_total = curvature;
    if (viscous) {
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

    double damage = state[kDamageSlot];
    const double strength = state[kStrengthSlot];
    if (b.breakage && beam::may_reach(strain_total, curvature_total, E, G, sec.radius, strength)) {
      const BondStress s = beam::stress_of(strain_total, curvature_total, E, G, sec.radius);
      if (s.sigma_vm >= strength) {
        if (!(p_.softening_ratio > 0)) {
          beam::write_broken(batch, k, s);
          continue;
        }
        damage = std::max(damage, softening_damage(s.sigma_vm, strength, p_.softening_ratio));
        if (damage >= 1) {
          beam::write_broken(batch, k, s);
          continue;
        }
        state[kDamageSlot] = damage;
      }
    }

    // Eq. 3 and 5, with the compressive axial modulus when the bond is shortened.
    const double axial_modulus = strain.x() < 0 ? compression_modulus_ : E;
    Vec3 material_force(axial_modulus * sec.area * strain.x(), a_s * G * sec.area * strain.y(),
                        a_s * G * sec.area * strain.z());
    Vec3 material_torque(2 * G * sec.second_moment * curvature.x(), E * sec.second_moment * curvature.y(),
                         E * sec.second_moment * curvature.z());
    double energy = 0.5 * l0 * (strain.dot(material_force) + curvature.dot(material_torque));
    if (viscous) {
      // The arm's stress on each component has that component's elastic modulus (E_b on the axial
      // and bending strains, G_b on shear and twist, as tensile bonds); its spring holds h / beta.
      const Vec3 arm_force(E * sec.area * arm_strain.x(), a_s * G * sec.area * arm_strain.y(),
                           a_s * G * sec.area * arm_strain.z());
      const Vec3 arm_torque(2 * G * sec.second_moment * arm_curvature.x(), E * sec.second_moment * arm_curvature.y(),
                            E * sec.second_moment * arm_curvature.z());
      material_force += arm_force;
      material_torque += arm_torque;
      energy += 0.5 * l0 * (arm_strain.dot(arm_force) + arm_curvature.dot(arm_torque)) / p_.viscous_modulus_ratio;
    }
    if (damage > 0) {
      const double intact = 1 - damage;
      material_force *= intact;
      material_torque *= intact;
      energy *= intact;
    }
    batch.energy[k] = energy;

    // Eq. 4 and 6-7: the numerical damping of beam_bond, unchanged by the effects.
    const Vec3 damping_force = b.damping * v12;
    const Vec3 damping_torque = rotational.torque(sec.second_moment, inv_l0, p.inertia[n1], p.inertia[n2], omega_rel);

    const beam::PairLoads loads =
        beam::pair_loads(g, material_force + damping_force, material_torque + damping_torque, e.swapped);
    batch.force[k] = loads.force_on_i;
    batch.torque_i[k] = loads.torque_on_i;
    batch.torque_j[k] = loads.torque_on_j;
  }
}

}  // namespace shard::beam_plus
