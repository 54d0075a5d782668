// Registration of the hertz_mindlin contact model: its name, version and parameter schema.
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "../common/contact_effects.hpp"
#include "../common/contact_params.hpp"
#include "hertz_mindlin_model.hpp"
#include "shard/plugin.hpp"

namespace {

shard::PluginInfo hertz_mindlin_info() {
  using shard::ParamSpec;
  const shard::HertzMindlinMaterial defaults;
  namespace cp = shard::contact_params;
  const ParamSpec shear = cp::shear_modulus(defaults.shear_modulus);
  const ParamSpec poisson = cp::poisson_ratio(defaults.poisson_ratio);
  const ParamSpec friction = cp::friction(defaults.friction);
  const ParamSpec restitution = cp::restitution(defaults.restitution);
  std::vector<ParamSpec> params{shear, poisson, friction, restitution};
  for (auto& spec : shard::contact::contact_effect_params(/*with_cohesion=*/true)) params.push_back(std::move(spec));
  // 1.1: the effect policies cohesion and support_friction (docs/reference/effects.md), which replace hertz_mindlin_plus;
  // 1.2: materials, G and nu per material, friction and restitution per pair (docs/reference/materials.md).
  return {shard::PluginKind::Contact, "hertz_mindlin", "1.2.0",
          "Hertz normal and Mindlin tangential spring with restitution damping and Coulomb friction; effect "
          "policies cohesion, support_friction (docs/reference/effects.md)",
          std::move(params)};
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_contact(hertz_mindlin_info(), [](const shard::ParamSet& params) {
    return std::make_unique<shard::HertzMindlin>(shard::HertzMindlin::from(params));
  });
}
