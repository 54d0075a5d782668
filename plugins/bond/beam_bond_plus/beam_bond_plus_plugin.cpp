// Registers beam_bond_plus: beam_bond's parameters (same names, units and defaults) plus one
// parameter per effect, each with the neutral value at which the effect is off.
#include <limits>
#include <memory>
#include <optional>

#include "beam_bond_plus_model.hpp"
#include "shard/plugin.hpp"

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

shard::ParamSpec number(const char* name, const char* unit, const char* doc, double value, double min,
                        bool min_exclusive, double max = kInf, std::optional<double> neutral = std::nullopt) {
  shard::ParamSpec s;
  s.name = name;
  s.type = shard::ParamType::Number;
  s.unit = unit;
  s.doc = doc;
  s.default_value = value;
  s.min = min;
  s.min_exclusive = min_exclusive;
  s.max = max;
  s.neutral = neutral;
  return s;
}

shard::PluginInfo beam_bond_plus_info() {
  shard::PluginInfo info;
  info.kind = shard::PluginKind::Bond;
  info.name = "beam_bond_plus";
  info.version = "1.0.0";
  info.doc = "beam_bond + Weibull strength scatter, cohesive softening, Kelvin-Voigt viscosity, "
             "tension/compression asymmetry (docs/effects.md)";
  auto& ps = info.params;
  // beam_bond's own parameters.
  ps.push_back(number("youngs_modulus", "Pa", "bond Young's modulus E_b (eq. 3, 5)", 12.8e6, 0, true));
  ps.push_back(number("shear_modulus", "Pa", "bond shear modulus G_b; 0 = E_b / (2 (1 + nu_b))", 0, 0, false));
  ps.push_back(number("poisson_ratio", "1", "bond Poisson ratio nu_b, used when shear_modulus = 0", 0.25, -1, true, 0.5));
  ps.push_back(number("shear_coefficient", "1", "Timoshenko shear coefficient a_s (eq. 3)", 0.9, 0, true, 1));
  ps.push_back(number("radius_ratio", "1", "bond radius over the smaller particle radius, lambda", 1, 0, true));
  ps.push_back(number("damping", "N s/m", "viscous coefficient d on the bond strain rate (eq. 4)", 0, 0, false, kInf, 0.0));
  ps.push_back(number("rotational_damping", "1",
                      "factor on the eq. 6 torque damping sqrt(k I_r); 1 = as printed (damping ratio 0.5), 0 = off", 1,
                      0, false, kInf, 0.0));
  ps.push_back(number("critical_stress", "Pa",
                      "mean von Mises strength sigma_v,crit (eq. 10); with m > 0 the mean of the Weibull law", 0.24e6, 0,
                      true, kInf, kInf));
  shard::ParamSpec breakage;
  breakage.name = "breakage";
  breakage.type = shard::ParamType::Boolean;
  breakage.doc = "bonds fail at their strength; false for elastic calibration (no softening either)";
  breakage.default_value = true;
  breakage.neutral = 0;
  ps.push_back(breakage);
  // The effects.
  ps.push_back(number("strength_weibull_modulus", "1",
                      "Weibull modulus m of the per-bond strength (mean critical_stress); 0 = no scatter", 0, 0, false,
                      kInf, 0.0));
  // An integer parameter: the number helper, retyped (2^53 keeps every value exact in a double).
  auto seed = number("strength_seed", "1", "seed of the per-bond strength hash (with the two stable ids)", 0, 0, false,
                     9007199254740992.0);
  seed.type = shard::ParamType::Integer;
  ps.push_back(seed);
  ps.push_back(number("softening_ratio", "1",
                      "linear softening over a further strain softening_ratio sigma_crit / E_b after the peak; 0 = brittle",
                      0, 0, false, kInf, 0.0));
  ps.push_back(number("viscosity_time", "s",
                      "Kelvin-Voigt time tau_v: stress E_b (Gamma + tau_v dGamma/dt), eta = E_b tau_v; 0 = elastic", 0, 0,
                      false, kInf, 0.0));
  ps.push_back(number("compression_stiffness_ratio", "1",
                      "axial stiffness in compression over E_b A_b / l0; 1 = symmetric", 1, 0, true, kInf, 1.0));
  return info;
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_bond(beam_bond_plus_info(), [](const shard::ParamSet& p) -> std::unique_ptr<shard::BondModel> {
    return std::make_unique<shard::beam_plus::BeamBondPlus>(shard::beam_plus::BeamBondPlusParams::from(p));
  });
}
