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
}

std::size_t BeamBond::state_size() const { return kStateSize; }

void BeamBond::initialize(BondBatch& batch) const {
  const ParticleView& p = batch.particles;
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Ends e = ends_of(p, batch.i[k], batch.j[k]);
    const Reference ref = reference_of(p.position[e.first], p.position[e.second], p.orientation[e.first],
                                       p.orientation[e.second]);
    if (!(ref.l0 > 0)) throw std::invalid_argument("beam_bond: a bond joins two particles at the same position");
    store(batch.state + k * kStateSize, ref);
  }
}

// Eq. 12: t_bond = 0.17 sqrt(m / K), lightest bonded particle, stiffest bond K = E_b A_b / l0.
// The "with damping" name only when there is a stiffest bond to shorten: no bonds, no limit.
TimeStepLimit BeamBond::time_step_limit(const BondBatch& batch) const {
  TimeStepLimit limit;
  limit.name = p_.damping > 0 ? "beam_bond t_bond (eq. 12, with eq. 4's damping)" : "beam_bond t_bond (eq. 12)";
  limit.critical = eq12_step(batch, kStateSize, p_.radius_ratio, {p_.youngs_modulus, p_.youngs_modulus}, p_.damping);
  limit.recommended = limit.critical;
  return limit;
}

// The per-bond path: the reference the blocked path is checked against bit for bit, and what
// runs the lanes the blocked path leaves (near failure, large rotations, off-unit quaternions).
void BeamBond::compute_bond(BondBatch& batch, std::size_t k) const {
  const ParticleView& p = batch.particles;
  const double E = p_.youngs_modulus;
  const double G = shear_modulus_;
  const double a_s = p_.shear_coefficient;
  const bool viscous_force = block_.viscous_force;

  const Ends e = ends_of(p, batch.i[k], batch.j[k]);
  const Index n1 = e.first, n2 = e.second;
  const Reference ref = load(batch.state + k * kStateSize);
  const double l0 = ref.l0;
  const double inv_l0 = 1 / l0;
  const Section sec = section_of(p_.radius_ratio, p.radius[n1], p.radius[n2]);
  const Deformation g = deform(ref, p.position[n1], p.position[n2], p.orientation[n1], p.orientation[n2]);

  // Strain and curvature vectors, bond frame.
  const auto [strain, curvature] = strain_curvature(g, inv_l0);  // Gamma, kappa

  if (p_.breakage && may_reach(strain, curvature, E, G, sec.radius, p_.critical_stress)) {
    const BondStress s = stress_of(strain, curvature, E, G, sec.radius);
    if (s.sigma_vm >= p_.critical_stress) {
      write_broken(batch, k, s);
      return;
    }
  }

  // Eq. 3 and 5: elastic force and torque, bond frame.
  const Vec3 elastic_force(E * sec.area * strain.x(), a_s * G * sec.area * strain.y(), a_s * G * sec.area * strain.z());
  const Vec3 elastic_torque(2 * G * sec.second_moment * curvature.x(), E * sec.second_moment * curvature.y(),
                            E * sec.second_moment * curvature.z());
  batch.energy[k] = 0.5 * l0 * (strain.dot(elastic_force) + curvature.dot(elastic_torque));

  // Eq. 4: viscous force on the objective strain rate v12 = l0 dGamma/dt; eq. 6-7: viscous torque
  // on Omega_rel = d theta / dt. Both zero for rigid motion.
  const Rates r = rates_of(g, p.velocity[n1], p.velocity[n2], p.omega[n1], p.omega[n2], viscous_force);
  Vec3 force = elastic_force;
  if (viscous_force) force += p_.damping * r.v12;
  const Vec3 damping_torque = rotational_.torque(sec.second_moment, inv_l0, p.inertia[n1], p.inertia[n2], r.omega_rel);

  const PairLoads loads = pair_loads(g, force, elastic_torque + damping_torque, e.swapped);
  batch.force[k] = loads.force_on_i;
  batch.torque_i[k] = loads.torque_on_i;
  batch.torque_j[k] = loads.torque_on_j;
}

void BeamBond::compute_reference(BondBatch& batch) const {
  for (std::size_t k = 0; k < batch.count; ++k) compute_bond(batch, k);
}

// Gather a block into lanes, evaluate it in one vectorised loop, scatter; the lanes the loop
// leaves go through the per-bond path.
void BeamBond::compute(BondBatch& batch) const {
  const ParticleView& p = batch.particles;

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
    in.state = batch.state + base * kStateSize;
    out.force = batch.force[base].data();
    out.torque_i = batch.torque_i[base].data();
    out.torque_j = batch.torque_j[base].data();
    out.energy = batch.energy + base;
    block_step_(in, out, n, block_);
    for (std::size_t l = 0; l < n; ++l)
      if (out.fallback[l]) compute_bond(batch, base + l);
  }
}

}  // namespace shard::beam
