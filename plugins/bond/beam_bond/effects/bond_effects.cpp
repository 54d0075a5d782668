#include "bond_effects.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "beam_bond_schema.hpp"
#include "weibull_strength.hpp"

namespace shard::beam {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<BondEffectPolicy> make_policies() {
  std::vector<BondEffectPolicy> out;
  out.push_back({"weibull_strength",
                 "per-bond strength from a Weibull law with mean critical_stress (weibull_strength.hpp)",
                 {number_param("strength_weibull_modulus", "1",
                               "Weibull modulus m of the per-bond strength (mean critical_stress); 0 = no scatter", 0, 0,
                               false, kInf, 0.0),
                  number_param("strength_cv", "1",
                               "the same Weibull law given by its coefficient of variation (std / mean of the "
                               "per-bond strength) instead of m; 0 = no scatter; not with strength_weibull_modulus",
                               0, 0, false, kMaxStrengthCv, 0.0)}});
  // An integer parameter: the number helper, retyped (2^53 keeps every value exact in a double).
  // No neutral value: the seed alone changes nothing while m = 0.
  auto seed = number_param("strength_seed", "1", "seed of the per-bond strength hash (with the two stable ids)", 0, 0,
                           false, 9007199254740992.0);
  seed.type = ParamType::Integer;
  out.front().params.push_back(seed);
  out.push_back({"softening",
                 "linear cohesive softening after the peak stress, damage in the state (cohesive_softening.hpp)",
                 {number_param("softening_ratio", "1",
                               "linear softening over a further strain softening_ratio sigma_crit / E_b after the peak; "
                               "0 = brittle",
                               0, 0, false, kInf, 0.0)}});
  out.push_back({"viscosity",
                 "standard linear solid: a Maxwell arm beside the beam, also in the breakage check (maxwell_arm.hpp)",
                 {number_param("viscosity_time", "s",
                               "viscosity eta = E_b tau_v of a Maxwell arm beside the elastic beam (standard linear "
                               "solid); slow loading sees E_b (Gamma + tau_v dGamma/dt); 0 = elastic",
                               0, 0, false, kInf, 0.0),
                  // No neutral value of its own: the arm is off while viscosity_time = 0.
                  number_param("viscous_modulus_ratio", "1",
                               "the Maxwell arm's spring over E_b: fast loading sees (1 + ratio) E_b; relaxation time "
                               "tau_v / ratio",
                               1, 0, true)}});
  out.push_back({"compression_asymmetry",
                 "axial stiffness in compression r times that in tension (compression_asymmetry.hpp)",
                 {number_param("compression_stiffness_ratio", "1",
                               "axial stiffness in compression over E_b A_b / l0; 1 = symmetric", 1, 0, true, kInf,
                               1.0)}});
  return out;
}

std::string valid_names() {
  std::string s;
  for (const auto& p : bond_effect_policies()) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

}  // namespace

const std::vector<BondEffectPolicy>& bond_effect_policies() {
  static const std::vector<BondEffectPolicy> policies = make_policies();
  return policies;
}

std::vector<ParamSpec> bond_effect_params() {
  std::vector<ParamSpec> ps;
  ParamSpec effects;
  effects.name = "effects";
  effects.type = ParamType::String;
  effects.doc = "effect policies composed into the law, e.g. \"softening, viscosity\" (one of: " + valid_names() +
                "); a policy whose parameter is away from its neutral value is on without being named";
  effects.default_value = std::string();
  ps.push_back(effects);
  for (const auto& policy : bond_effect_policies())
    for (const auto& spec : policy.params) ps.push_back(spec);
  return ps;
}

BondEffects BondEffects::from(const ParamSet& p) {
  BondEffects e;
  e.strength_weibull_modulus = p.number("strength_weibull_modulus");
  e.strength_cv = p.number("strength_cv");
  if (e.strength_weibull_modulus > 0 && e.strength_cv > 0)
    throw std::invalid_argument("beam_bond: strength_weibull_modulus and strength_cv both set; they give the same "
                                "Weibull law two ways: keep one");
  e.strength_seed = static_cast<std::uint64_t>(p.integer("strength_seed"));
  e.softening_ratio = p.number("softening_ratio");
  e.viscosity_time = p.number("viscosity_time");
  e.viscous_modulus_ratio = p.number("viscous_modulus_ratio");
  e.compression_stiffness_ratio = p.number("compression_stiffness_ratio");
  for (const auto& name : p.names("effects")) {
    const auto& policies = bond_effect_policies();
    if (std::none_of(policies.begin(), policies.end(), [&](const BondEffectPolicy& q) { return q.name == name; }))
      throw std::invalid_argument("beam_bond: effects names '" + name + "', which is no effect policy; valid: " +
                                  valid_names() + " (docs/reference/effects.md)");
    e.named.push_back(name);
  }
  return e;
}

bool BondEffects::any() const {
  if (!named.empty()) return true;
  for (const auto& policy : bond_effect_policies())
    for (const auto& spec : policy.params) {
      if (!spec.neutral) continue;
      const double value = spec.name == "strength_weibull_modulus" ? strength_weibull_modulus
                           : spec.name == "strength_cv"            ? strength_cv
                           : spec.name == "softening_ratio"        ? softening_ratio
                           : spec.name == "viscosity_time"         ? viscosity_time
                                                                   : compression_stiffness_ratio;
      if (value != *spec.neutral) return true;
    }
  return false;
}

double BondEffects::weibull_modulus() const {
  if (strength_weibull_modulus > 0) return strength_weibull_modulus;
  return strength_cv > 0 ? weibull_modulus_for_cv(strength_cv) : 0.0;
}

}  // namespace shard::beam
