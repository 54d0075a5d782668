// crushing_bond: the seed's beam bond (eq. 3-10, through Shard's installed beam helpers) plus one
// effect the shipped library lacks: a bond also fails when it is crushed. Written in the tutorial
// (docs/tutorial.md part 6) from `shard new-plugin bond crushing_bond`.
//
// Physics: a cemented contact is weaker in compression than its grains: the binder bridge crushes.
// The bond's largest compressive fibre stress is
//   sigma_c = max(0, -E_b Gamma_x) + E_b r_b |kappa_bend|          (axial compression + bending),
// and the bond breaks when sigma_c >= sigma_crush. Written with the ratio
//   crushing_ratio = sigma_crit / sigma_crush    (1; 0 = never crushes, the neutral value),
// so the effect is off at 0 and the model is beam_bond's. Under a loading pin of a bending test the
// bonds carry the pin force in compression: ~1 N on a 4.2e-6 m^2 bond of the tiny beam is 0.24 MPa,
// Table I's sigma_crit, so a crushing ratio of order 1 crushes the surface under the pins first.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "shard/beam/beam_geometry.hpp"
#include "shard/beam/beam_stress.hpp"
#include "shard/beam/bond_step.hpp"
#include "shard/plugin.hpp"

namespace {

using shard::Vec3;

struct Params {
  double youngs, shear, shear_coefficient, radius_ratio, damping, rotational_damping, strength;
  bool breakage;
  double crushing_ratio;  // sigma_crit / sigma_crush, 1 (the effect; neutral 0)
};

class CrushingBond final : public shard::BondModel {
 public:
  explicit CrushingBond(const Params& p) : p_(p) {
    if (!(p_.youngs > 0) || !(p_.shear > 0)) throw std::invalid_argument("crushing_bond: E_b and G_b must be > 0");
  }

  std::size_t state_size() const override { return shard::beam::kStateSize; }

  void initialize(shard::BondBatch& b) const override {
    const auto& p = b.particles;
    for (std::size_t k = 0; k < b.count; ++k) {
      const auto [n1, n2, swapped] = shard::beam::ends_of(p, b.i[k], b.j[k]);
      shard::beam::store(b.state + k * shard::beam::kStateSize,
                         shard::beam::reference_of(p.position[n1], p.position[n2], p.orientation[n1], p.orientation[n2]));
    }
  }

  // Eq. 12 with eq. 4's dashpot (the shipped beam's limit); crushing adds no stiffness.
  shard::TimeStepLimit time_step_limit(const shard::BondBatch& b) const override {
    const double t = shard::beam::eq12_step(b, shard::beam::kStateSize, p_.radius_ratio, {p_.youngs, p_.youngs}, p_.damping);
    return {"crushing_bond t_bond (eq. 12)", t, t};
  }

  bool writes_every_output() const override { return true; }  // intact bonds in full, broken ones zeroed

  void compute(shard::BondBatch& b) const override {
    namespace beam = shard::beam;
    const auto& p = b.particles;
    const double E = p_.youngs, G = p_.shear;
    const beam::RotationalDamping rotational(p_.rotational_damping, E, G);
    for (std::size_t k = 0; k < b.count; ++k) {
      const auto [n1, n2, swapped] = beam::ends_of(p, b.i[k], b.j[k]);
      const beam::Reference ref = beam::load(b.state + k * beam::kStateSize);
      const double inv_l0 = 1 / ref.l0;
      const auto [r, area, second_moment] = beam::section_of(p_.radius_ratio, p.radius[n1], p.radius[n2]);
      const beam::Deformation g = beam::deform(ref, p.position[n1], p.position[n2], p.orientation[n1], p.orientation[n2]);
      const auto [strain, curvature] = beam::strain_curvature(g, inv_l0);  // Gamma, kappa
      if (p_.breakage) {
        const shard::BondStress s = beam::stress_of(strain, curvature, E, G, r);
        // The effect: the compressed fibre of the bond against sigma_crush = sigma_crit / ratio.
        const double crushing = std::max(0.0, -E * strain.x()) + s.bending;
        if (s.sigma_vm >= p_.strength || p_.crushing_ratio * crushing >= p_.strength) {
          beam::write_broken(b, k, s);
          continue;
        }
      }
      const beam::Rates rates =
          beam::rates_of(g, p.velocity[n1], p.velocity[n2], p.omega[n1], p.omega[n2], p_.damping != 0);
      const Vec3 force(E * area * strain.x(), p_.shear_coefficient * G * area * strain.y(),
                       p_.shear_coefficient * G * area * strain.z());  // eq. 3, 5
      const Vec3 torque(2 * G * second_moment * curvature.x(), E * second_moment * curvature.y(),
                        E * second_moment * curvature.z());
      b.energy[k] = 0.5 * ref.l0 * (strain.dot(force) + curvature.dot(torque));
      const Vec3 damping_torque = rotational.torque(second_moment, inv_l0, p.inertia[n1], p.inertia[n2], rates.omega_rel);
      const beam::PairLoads loads = beam::pair_loads(g, force + p_.damping * rates.v12, torque + damping_torque, swapped);
      b.force[k] = loads.force_on_i;
      b.torque_i[k] = loads.torque_on_i;
      b.torque_j[k] = loads.torque_on_j;
    }
  }

 private:
  Params p_;
};

shard::ParamSpec number(const char* name, const char* unit, const char* doc, double value, double min,
                        std::optional<double> neutral = std::nullopt) {
  shard::ParamSpec s;
  s.name = name, s.unit = unit, s.doc = doc, s.default_value = value, s.min = min, s.neutral = neutral;
  return s;
}

shard::PluginInfo info() {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  shard::ParamSpec breakage;
  breakage.name = "breakage", breakage.type = shard::ParamType::Boolean, breakage.doc = "bonds fail";
  breakage.default_value = true, breakage.neutral = 0;
  return {shard::PluginKind::Bond,
          "crushing_bond",
          "0.1.0",
          "the seed's beam bond that also crushes in compression (tutorial part 6)",
          {number("youngs_modulus", "Pa", "bond Young's modulus E_b", 12.8e6, 0),
           number("shear_modulus", "Pa", "bond shear modulus G_b; 0 = E_b / (2 (1 + nu_b))", 0, 0),
           number("poisson_ratio", "1", "bond Poisson ratio nu_b", 0.25, -1),
           number("shear_coefficient", "1", "Timoshenko shear coefficient a_s", 0.9, 0),
           number("radius_ratio", "1", "bond radius over the smaller particle radius", 1, 0),
           number("damping", "N s/m", "viscous coefficient on the bond strain rate (eq. 4)", 0, 0, 0.0),
           number("rotational_damping", "1", "factor on the eq. 6 torque damping", 1, 0, 0.0),
           number("critical_stress", "Pa", "von Mises strength sigma_crit (eq. 10)", 0.24e6, 0, kInf),
           breakage,
           number("crushing_ratio", "1", "sigma_crit / sigma_crush: a bond also breaks when its compressed fibre "
                  "reaches sigma_crush; 0 = never crushes", 0, 0, 0.0)}};
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_bond(info(), [](const shard::ParamSet& p) -> std::unique_ptr<shard::BondModel> {
    const double E = p.number("youngs_modulus");
    const double G = p.number("shear_modulus") > 0 ? p.number("shear_modulus") : E / (2 * (1 + p.number("poisson_ratio")));
    return std::make_unique<CrushingBond>(Params{E, G, p.number("shear_coefficient"), p.number("radius_ratio"),
                                                 p.number("damping"), p.number("rotational_damping"),
                                                 p.number("critical_stress"), p.flag("breakage"),
                                                 p.number("crushing_ratio")});
  });
}
