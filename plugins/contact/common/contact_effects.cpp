#include "contact_effects.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace shard::contact {
namespace {

ParamSpec number(const char* name, const char* unit, const char* doc, double value, double neutral,
                 ParamScope scope = ParamScope::Model) {
  return {.name = name, .unit = unit, .doc = doc, .default_value = value, .min = 0.0, .neutral = neutral, .scope = scope};
}

std::string valid_names(bool with_cohesion) {
  std::string s;
  for (const auto& p : contact_effect_policies(with_cohesion)) {
    if (!s.empty()) s += ", ";
    s += p.name;
  }
  return s;
}

}  // namespace

std::vector<ContactEffectPolicy> contact_effect_policies(bool with_cohesion) {
  std::vector<ContactEffectPolicy> out;
  if (with_cohesion)
    out.push_back({"cohesion", "pull per contact area between touching particles (linear cohesion, not at walls)",
                   number("cohesion_stress", "Pa",
                          "pull per contact area pi R* delta between touching particles (linear cohesion, not at walls); "
                          "0 = none",
                          0.0, 0.0)});
  out.push_back({"support_friction", "Coulomb friction of its own at particle-wall contacts (supports, pins)",
                 number("support_friction_ratio", "1",
                        "Coulomb friction at particle-wall contacts (supports, pins) over the particles' friction; "
                        "1 = the same",
                        1.0, 1.0)});
  out.push_back({"rolling_resistance",
                 "a couple against relative rolling, elastic-plastic, capped at mu_r R* F_n (Ai et al. 2011, model C)",
                 number("rolling_friction", "1",
                        "coefficient of rolling friction mu_r: the rolling couple's cap over R* F_n (a sphere rolling on a "
                        "plane decelerates at 5/7 mu_r g); 0 = none",
                        0.0, 0.0, ParamScope::Pair)});
  return out;
}

std::vector<ParamSpec> contact_effect_params(bool with_cohesion) {
  std::vector<ParamSpec> ps;
  ParamSpec effects;
  effects.name = "effects";
  effects.type = ParamType::String;
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on a chain of string + literal.
  std::string doc = "effect policies composed into the law, e.g. \"";
  doc += with_cohesion ? "cohesion, support_friction" : "support_friction";
  doc += "\" (one of: ";
  doc += valid_names(with_cohesion);
  doc += "); a policy whose parameter is away from its neutral value is on without being named";
  effects.doc = doc;
  effects.default_value = std::string();
  ps.push_back(effects);
  for (const auto& policy : contact_effect_policies(with_cohesion)) ps.push_back(policy.param);
  return ps;
}

ContactEffects ContactEffects::from(const ParamSet& p, const char* law, bool with_cohesion) {
  ContactEffects e;
  if (with_cohesion) e.cohesion_stress = p.number("cohesion_stress");
  e.support_friction_ratio = p.number("support_friction_ratio");
  e.rolling_friction = p.number("rolling_friction");
  const auto policies = contact_effect_policies(with_cohesion);
  for (const auto& name : p.names("effects")) {
    if (std::none_of(policies.begin(), policies.end(), [&](const ContactEffectPolicy& q) { return q.name == name; })) {
      std::string what = law;
      what += ": effects names '";
      what += name;
      what += "', which is no effect policy of this law; valid: ";
      what += valid_names(with_cohesion);
      what += " (docs/reference/effects.md)";
      throw std::invalid_argument(what);
    }
    e.named.push_back(name);
  }
  if (!(e.cohesion_stress >= 0.0)) throw std::invalid_argument(std::string(law) + ": cohesion_stress must be >= 0 Pa");
  if (!(e.support_friction_ratio >= 0.0))
    throw std::invalid_argument(std::string(law) + ": support_friction_ratio must be >= 0");
  if (!(e.rolling_friction >= 0.0)) throw std::invalid_argument(std::string(law) + ": rolling_friction must be >= 0");
  return e;
}

bool ContactEffects::rolling_on(const std::vector<double>& mu_r_per_pair) const {
  const bool named_here = std::find(named.begin(), named.end(), "rolling_resistance") != named.end();
  return named_here || std::any_of(mu_r_per_pair.begin(), mu_r_per_pair.end(), [](double mu_r) { return mu_r != 0.0; });
}

EffectSwitches ContactEffects::switches() const {
  EffectSwitches on;
  for (const auto& policy : contact_effect_policies(true)) {
    if (policy.name == "rolling_resistance") continue;  // per pair of materials: rolling_on
    const bool cohesion = policy.name == "cohesion";
    const double value = cohesion ? cohesion_stress : support_friction_ratio;
    const bool named_here = std::find(named.begin(), named.end(), policy.name) != named.end();
    (cohesion ? on.cohesion : on.support_friction) = named_here || value != *policy.param.neutral;
  }
  return on;
}

ComposedEffects::ComposedEffects(const ContactEffects& effects)
    : given(effects), on(effects.switches()), rolling_friction{effects.rolling_friction} {
  on.rolling_resistance = given.rolling_on(rolling_friction);
}

void ComposedEffects::set_pairs(const std::vector<ParamSet>& pairs) {
  std::vector<double> mu_r;
  mu_r.reserve(pairs.size());
  for (const ParamSet& pair : pairs) {
    // A table made in code may leave the effect out: off, its neutral value.
    const double value = pair.has("rolling_friction") ? pair.number("rolling_friction") : 0.0;
    if (!(value >= 0.0)) throw std::invalid_argument("rolling_friction must be >= 0");
    mu_r.push_back(value);
  }
  rolling_friction = std::move(mu_r);
  on.rolling_resistance = given.rolling_on(rolling_friction);
}

EffectSizes ComposedEffects::sizes() const {
  EffectSizes s = given.sizes();
  s.rolling_friction = rolling_friction.data();
  return s;
}

}  // namespace shard::contact
