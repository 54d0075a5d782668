// crushing_bond: the seed's beam bond (eq. 3-10: Shard's installed beam law, not a copy) plus one
// effect the shipped library lacks: a bond also fails when it is crushed. Written in the tutorial
// (docs/tutorials/measurement-loop.md part 6) from `shard new-plugin bond crushing_bond`.
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
#include "shard/beam/beam_step.hpp"
#include "shard/beam/bond_step.hpp"
#include "shard/plugin.hpp"

namespace {

// The effect, as an extra break criterion of the installed beam law (shard/beam/beam_law.hpp):
// a bound false only when the compressed fibre certainly stays below sigma_crush (|(a, b)| <=
// |a| + |b| on the bending), and the decision on the stresses the law computed.
struct Crushing {
  double ratio;  // sigma_crit / sigma_crush

  template <class T>
  auto may_break(const T (&strain)[3], const T (&curvature)[3], const T& radius, const shard::beam::LawConstants& c) const {
    using shard::lanes::abs, shard::lanes::max;  // for double; a SIMD lane type brings its own (ADL)
    const double E = c.youngs;
    const T fibre = max(-E * strain[0], T(0.0)) + E * radius * (abs(curvature[1]) + abs(curvature[2]));
    return ratio * fibre >= (1 - 1e-12) * c.strength;
  }
  bool breaks(const double (&strain)[3], const double (&)[3], const shard::BondStress& s,
              const shard::beam::LawConstants& c) const {
    const double crushing = std::max(0.0, -c.youngs * strain[0]) + s.bending;
    return ratio * crushing >= c.strength;
  }
};

class CrushingBond final : public shard::BondModel {
 public:
  CrushingBond(const shard::beam::LawConstants& law, double crushing_ratio) : law_(law), crushing_{crushing_ratio} {
    if (!(law_.youngs > 0) || !(law_.shear > 0)) throw std::invalid_argument("crushing_bond: E_b and G_b must be > 0");
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
    const double t = shard::beam::eq12_step(b, shard::beam::kStateSize, law_.radius_ratio, {law_.youngs, law_.youngs},
                                            law_.damping);
    return {"crushing_bond t_bond (eq. 12)", t, t};
  }

  bool writes_every_output() const override { return true; }  // intact bonds in full, broken ones zeroed

  // The seed's beam law bond by bond (width 1), with the crushing criterion beside its von Mises one.
  void compute(shard::BondBatch& b) const override {
    for (std::size_t k = 0; k < b.count; ++k) shard::beam::step_bond(b, k, shard::beam::kStateSize, law_, crushing_);
  }

 private:
  shard::beam::LawConstants law_;
  Crushing crushing_;
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
    shard::beam::LawConstants law;
    law.youngs = p.number("youngs_modulus");
    law.shear = p.number("shear_modulus") > 0 ? p.number("shear_modulus")
                                              : law.youngs / (2 * (1 + p.number("poisson_ratio")));
    law.shear_coefficient = p.number("shear_coefficient");
    law.radius_ratio = p.number("radius_ratio");
    law.damping = p.number("damping");
    law.viscous_force = law.damping != 0;
    law.strength = p.number("critical_stress");
    law.breakage = p.flag("breakage");
    const shard::beam::RotationalDamping rotational(p.number("rotational_damping"), law.youngs, law.shear);
    law.bend_scale = rotational.bend_scale();
    law.twist_over_bend = rotational.twist_over_bend();
    return std::make_unique<CrushingBond>(law, p.number("crushing_ratio"));
  });
}
