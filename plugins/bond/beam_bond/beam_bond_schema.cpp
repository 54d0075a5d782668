#include "beam_bond_schema.hpp"

#include "effects/bond_effects.hpp"

namespace shard::beam {

ParamSpec number_param(const char* name, const char* unit, const char* doc, double value, double min,
                       bool min_exclusive, double max, std::optional<double> neutral) {
  ParamSpec s;
  s.name = name;
  s.type = ParamType::Number;
  s.unit = unit;
  s.doc = doc;
  s.default_value = value;
  s.min = min;
  s.min_exclusive = min_exclusive;
  s.max = max;
  s.neutral = neutral;
  return s;
}

std::vector<ParamSpec> beam_bond_params() {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<ParamSpec> ps;
  ps.push_back(number_param("youngs_modulus", "Pa", "bond Young's modulus E_b (eq. 3, 5)", 12.8e6, 0, true));
  ps.push_back(number_param("shear_modulus", "Pa", "bond shear modulus G_b; 0 = E_b / (2 (1 + nu_b))", 0, 0, false));
  ps.push_back(number_param("poisson_ratio", "1", "bond Poisson ratio nu_b, used when shear_modulus = 0", 0.25, -1,
                            true, 0.5));
  ps.push_back(number_param("shear_coefficient", "1", "Timoshenko shear coefficient a_s (eq. 3)", 0.9, 0, true, 1));
  ps.push_back(number_param("radius_ratio", "1", "bond radius over the smaller particle radius, lambda", 1, 0, true));
  ps.push_back(number_param("damping", "N s/m", "viscous coefficient d on the bond strain rate (eq. 4)", 0, 0, false,
                            kInf, 0.0));
  ps.push_back(number_param("rotational_damping", "1",
                            "factor on the eq. 6 torque damping sqrt(k I_r); 1 = as printed (damping ratio 0.5), 0 = off",
                            1, 0, false, kInf, 0.0));
  // No neutral value: "no breakage" is breakage = false (an infinite strength is no valid value).
  ps.push_back(number_param("critical_stress", "Pa",
                            "von Mises stress at which a bond breaks, sigma_v,crit (eq. 10)", 0.24e6, 0, true));
  ParamSpec breakage;
  breakage.name = "breakage";
  breakage.type = ParamType::Boolean;
  breakage.doc = "bonds fail at the critical stress; false for elastic calibration";
  breakage.default_value = true;
  breakage.neutral = 0;
  ps.push_back(breakage);
  for (auto& spec : bond_effect_params()) ps.push_back(std::move(spec));
  return ps;
}

}  // namespace shard::beam
