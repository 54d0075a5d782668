// Registers beam_bond_plus: beam_bond's parameters (same names, units and defaults) plus one
// parameter per effect, each with the neutral value at which the effect is off.
#include <limits>
#include <memory>
#include <optional>

#include "beam_bond_plus_model.hpp"
#include "beam_bond_schema.hpp"
#include "shard/plugin.hpp"

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using shard::beam::number_param;

shard::PluginInfo beam_bond_plus_info() {
  shard::PluginInfo info;
  info.kind = shard::PluginKind::Bond;
  info.name = "beam_bond_plus";
  info.version = "1.1.0";
  info.doc = "beam_bond + Weibull strength scatter, cohesive softening, standard-linear-solid (Maxwell arm) viscosity, "
             "tension/compression asymmetry (docs/effects.md)";
  // beam_bond's own parameters, with the two whose meaning the effects widen re-documented.
  info.params = shard::beam::beam_bond_params();
  auto& ps = info.params;
  for (auto& spec : ps) {
    if (spec.name == "critical_stress")
      spec.doc = "mean von Mises strength sigma_v,crit (eq. 10); with m > 0 the mean of the Weibull law";
    if (spec.name == "breakage")
      spec.doc = "bonds fail at their strength; false for elastic calibration (no softening either)";
  }
  // The effects.
  ps.push_back(number_param("strength_weibull_modulus", "1",
                      "Weibull modulus m of the per-bond strength (mean critical_stress); 0 = no scatter", 0, 0, false,
                      kInf, 0.0));
  // An integer parameter: the number helper, retyped (2^53 keeps every value exact in a double).
  auto seed = number_param("strength_seed", "1", "seed of the per-bond strength hash (with the two stable ids)", 0, 0, false,
                     9007199254740992.0);
  seed.type = shard::ParamType::Integer;
  ps.push_back(seed);
  ps.push_back(number_param("softening_ratio", "1",
                      "linear softening over a further strain softening_ratio sigma_crit / E_b after the peak; 0 = brittle",
                      0, 0, false, kInf, 0.0));
  ps.push_back(number_param("viscosity_time", "s",
                      "viscosity eta = E_b tau_v of a Maxwell arm beside the elastic beam (standard linear solid); "
                      "slow loading sees E_b (Gamma + tau_v dGamma/dt); 0 = elastic",
                      0, 0, false, kInf, 0.0));
  ps.push_back(number_param("viscous_modulus_ratio", "1",
                      "the Maxwell arm's spring over E_b: fast loading sees (1 + ratio) E_b; relaxation time "
                      "tau_v / ratio",
                      1, 0, true));
  ps.push_back(number_param("compression_stiffness_ratio", "1",
                      "axial stiffness in compression over E_b A_b / l0; 1 = symmetric", 1, 0, true, kInf, 1.0));
  return info;
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_bond(beam_bond_plus_info(), [](const shard::ParamSet& p) -> std::unique_ptr<shard::BondModel> {
    return std::make_unique<shard::beam_plus::BeamBondPlus>(shard::beam_plus::BeamBondPlusParams::from(p));
  });
}
