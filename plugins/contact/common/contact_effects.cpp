#include "contact_effects.hpp"

#include <algorithm>
#include <stdexcept>

namespace shard::contact {
namespace {

ParamSpec number(const char* name, const char* unit, const char* doc, double value, double neutral) {
  return {.name = name, .unit = unit, .doc = doc, .default_value = value, .min = 0.0, .neutral = neutral};
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
  const auto policies = contact_effect_policies(with_cohesion);
  for (const auto& name : p.names("effects")) {
    if (std::none_of(policies.begin(), policies.end(), [&](const ContactEffectPolicy& q) { return q.name == name; })) {
      std::string what = law;
      what += ": effects names '";
      what += name;
      what += "', which is no effect policy of this law; valid: ";
      what += valid_names(with_cohesion);
      what += " (docs/effects.md)";
      throw std::invalid_argument(what);
    }
    e.named.push_back(name);
  }
  if (!(e.cohesion_stress >= 0.0)) throw std::invalid_argument(std::string(law) + ": cohesion_stress must be >= 0 Pa");
  if (!(e.support_friction_ratio >= 0.0))
    throw std::invalid_argument(std::string(law) + ": support_friction_ratio must be >= 0");
  return e;
}

EffectSwitches ContactEffects::switches() const {
  EffectSwitches on;
  for (const auto& policy : contact_effect_policies(true)) {
    const bool cohesion = policy.name == "cohesion";
    const double value = cohesion ? cohesion_stress : support_friction_ratio;
    const bool named_here = std::find(named.begin(), named.end(), policy.name) != named.end();
    (cohesion ? on.cohesion : on.support_friction) = named_here || value != *policy.param.neutral;
  }
  return on;
}

}  // namespace shard::contact
