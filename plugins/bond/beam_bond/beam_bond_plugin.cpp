// Registers the beam bond with the host: its name, version and parameters with SI units.
#include <limits>
#include <memory>

#include "beam_bond_model.hpp"
#include "shard/plugin.hpp"

namespace {

shard::ParamSpec number(const char* name, const char* unit, const char* doc, double value, double min,
                        bool min_exclusive, double max = std::numeric_limits<double>::infinity()) {
  shard::ParamSpec s;
  s.name = name;
  s.type = shard::ParamType::Number;
  s.unit = unit;
  s.doc = doc;
  s.default_value = value;
  s.min = min;
  s.min_exclusive = min_exclusive;
  s.max = max;
  return s;
}

shard::PluginInfo beam_bond_info() {
  shard::PluginInfo info;
  info.kind = shard::PluginKind::Bond;
  info.name = "beam_bond";
  info.version = "1.0.0";
  info.doc = "Timoshenko beam bond, total quaternion formulation, von Mises breakage (seed eq. 3-12)";
  info.params.push_back(number("youngs_modulus", "Pa", "bond Young's modulus E_b (eq. 3, 5)", 12.8e6, 0, true));
  info.params.push_back(number("shear_modulus", "Pa", "bond shear modulus G_b; 0 = E_b / (2 (1 + nu_b))", 0, 0, false));
  info.params.push_back(number("poisson_ratio", "1", "bond Poisson ratio nu_b, used when shear_modulus = 0", 0.25,
                               -1, true, 0.5));
  info.params.push_back(number("shear_coefficient", "1", "Timoshenko shear coefficient a_s (eq. 3)", 0.9, 0, true, 1));
  info.params.push_back(number("radius_ratio", "1", "bond radius over the smaller particle radius, lambda", 1, 0, true));
  auto damping = number("damping", "N s/m", "viscous coefficient d on the bond strain rate (eq. 4)", 0, 0, false);
  damping.neutral = 0;
  info.params.push_back(damping);
  auto rotational = number("rotational_damping", "1",
                           "factor on the eq. 6 torque damping sqrt(k I_r); 1 = as printed (damping ratio 0.5), 0 = off",
                           1, 0, false);
  rotational.neutral = 0;
  info.params.push_back(rotational);
  auto critical = number("critical_stress", "Pa", "von Mises stress at which a bond breaks, sigma_v,crit (eq. 10)",
                         0.24e6, 0, true);
  critical.neutral = std::numeric_limits<double>::infinity();
  info.params.push_back(critical);
  shard::ParamSpec breakage;
  breakage.name = "breakage";
  breakage.type = shard::ParamType::Boolean;
  breakage.unit = "";
  breakage.doc = "bonds fail at the critical stress; false for elastic calibration";
  breakage.default_value = true;
  breakage.neutral = 0;
  info.params.push_back(breakage);
  return info;
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_bond(beam_bond_info(), [](const shard::ParamSet& p) -> std::unique_ptr<shard::BondModel> {
    return std::make_unique<shard::beam::BeamBond>(shard::beam::BeamBondParams::from(p));
  });
}
