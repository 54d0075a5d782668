#include "beam_bond_model.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "beam_batch.hpp"
#include "beam_geometry.hpp"
#include "beam_step.hpp"
#include "bond_step.hpp"
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
      block_step_(block_function(isa)) {
  if (!runs_here(isa))
    throw std::invalid_argument(std::string("beam_bond: this CPU cannot run the ") + name_of(isa) + " block step");
  block_.youngs = p_.youngs_modulus;
  block_.shear = shear_modulus_;
  block_.shear_coefficient = p_.shear_coefficient;
  block_.radius_ratio = p_.radius_ratio;
  block_.damping = p_.damping;
  block_.strength = p_.critical_stress;
  const RotationalDamping rotational(p_.rotational_damping, p_.youngs_modulus, shear_modulus_);
  block_.bend_scale = rotational.bend_scale();
  block_.twist_over_bend = rotational.twist_over_bend();
  block_.breakage = p_.breakage;
  block_.viscous_force = p_.damping != 0;
  if (!(p_.youngs_modulus > 0) || !(shear_modulus_ > 0) || !(p_.shear_coefficient > 0) || !(p_.radius_ratio > 0))
    throw std::invalid_argument("beam_bond: youngs_modulus, shear modulus, shear_coefficient and radius_ratio must be > 0");
  const BondEffects& fx = p_.effects;
  if (!(fx.strength_weibull_modulus >= 0) || !(fx.strength_cv >= 0) || !(fx.softening_ratio >= 0) ||
      !(fx.viscosity_time >= 0))
    throw std::invalid_argument(
        "beam_bond: strength_weibull_modulus, strength_cv, softening_ratio, viscosity_time must be >= 0");
  if (!(fx.viscous_modulus_ratio > 0) || !(fx.compression_stiffness_ratio > 0))
    throw std::invalid_argument("beam_bond: viscous_modulus_ratio and compression_stiffness_ratio must be > 0");
  block_.effects = fx.any();
  block_.arm = block_.effects && fx.viscous();
  block_.compression_modulus = fx.compression_stiffness_ratio * p_.youngs_modulus;
  block_.arm_modulus_ratio = fx.viscous_modulus_ratio;
  block_.softening_ratio = fx.softening_ratio;
  weibull_modulus_ = fx.weibull_modulus();
  if (weibull_modulus_ > 0) weibull_scale_ = weibull_scale(p_.critical_stress, weibull_modulus_);
}

std::size_t BeamBond::state_size() const {
  return !block_.effects ? kStateSize : block_.arm ? kViscousStateSize : kEffectsStateSize;
}

double BeamBond::strength_of(std::int64_t id_a, std::int64_t id_b) const {
  const BondEffects& fx = p_.effects;
  if (!(weibull_modulus_ > 0)) return p_.critical_stress;
  return weibull_quantile(bond_uniform(fx.strength_seed, id_a, id_b), weibull_scale_, weibull_modulus_);
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

BlockConstants BeamBond::constants_for(double dt) const {
  BlockConstants c = block_;
  if (c.arm) {  // the arm's factors depend on this batch's step
    const MaxwellArm arm(p_.effects.viscosity_time, p_.effects.viscous_modulus_ratio, dt);
    c.arm_decay = arm.decay;
    c.arm_gain = arm.gain;
  }
  return c;
}

void BeamBond::compute_reference(BondBatch& batch) const {
  const BlockConstants c = constants_for(batch.dt);
  for (std::size_t k = 0; k < batch.count; ++k) step_bond(batch, k, state_size(), c, NoExtraCriterion{});
}

// A block of bonds through the law at the SIMD width; the lanes it leaves (near failure, large
// rotations, off-unit quaternions, damaged bonds) through the same law at width 1.
void BeamBond::compute(BondBatch& batch) const {
  const ParticleView& p = batch.particles;
  const std::size_t stride = state_size();
  const BlockConstants constants = constants_for(batch.dt);

  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Quat) == 4 * sizeof(double));
  BlockOutput out;
  BlockInput in;
  in.id = p.id;
  in.position = reinterpret_cast<const double*>(p.position);
  in.velocity = reinterpret_cast<const double*>(p.velocity);
  in.orientation = reinterpret_cast<const double*>(p.orientation);
  in.omega = reinterpret_cast<const double*>(p.omega);
  in.radius = p.radius;
  in.inertia = p.inertia;
  for (std::size_t base = 0; base < batch.count; base += kBlockLanes) {
    const std::size_t n = std::min(kBlockLanes, batch.count - base);
    in.i = batch.i + base;
    in.j = batch.j + base;
    in.state = batch.state + base * stride;
    out.state = batch.state + base * stride;
    out.force = batch.force[base].data();
    out.torque_i = batch.torque_i[base].data();
    out.torque_j = batch.torque_j[base].data();
    out.energy = batch.energy + base;
    block_step_(in, out, n, constants);
    for (std::uint64_t left = out.fallback; left != 0; left &= left - 1)
      step_bond(batch, base + static_cast<std::size_t>(std::countr_zero(left)), stride, constants, NoExtraCriterion{});
  }
}

}  // namespace shard::beam
