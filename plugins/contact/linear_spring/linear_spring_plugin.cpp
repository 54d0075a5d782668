// Registration of the linear_spring contact model: its name, version and parameter schema.
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "../common/contact_effects.hpp"
#include "../common/contact_params.hpp"
#include "linear_spring_model.hpp"
#include "shard/plugin.hpp"

namespace {

shard::PluginInfo linear_spring_info() {
  using shard::ParamSpec;
  const shard::LinearSpringParameters defaults;
  ParamSpec normal{.name = "normal_stiffness",
                   .unit = "N/m",
                   .doc = "normal spring k_n (default: order of the Hertz stiffness of 0.35 mm Table I spheres)",
                   .default_value = defaults.normal_stiffness,
                   .min = 0.0,
                   .min_exclusive = true,
                   .neutral = std::nullopt,
                   .scope = shard::ParamScope::Pair};
  ParamSpec ratio{.name = "tangential_stiffness_ratio",
                  .unit = "1",
                  .doc = "k_t / k_n; 2/7 makes the tangential and normal oscillations of spheres equally fast",
                  .default_value = defaults.tangential_stiffness_ratio,
                  .min = 0.0,
                  .min_exclusive = true,
                  .neutral = std::nullopt,
                  .scope = shard::ParamScope::Pair};
  const ParamSpec friction = shard::contact_params::friction(defaults.friction);
  const ParamSpec restitution = shard::contact_params::restitution(defaults.restitution);
  std::vector<ParamSpec> params{normal, ratio, friction, restitution};
  for (auto& spec : shard::contact::contact_effect_params(/*with_cohesion=*/false)) params.push_back(std::move(spec));
  // 1.1: the effect policy support_friction (docs/reference/effects.md); 1.2: materials, every parameter per pair
  // (docs/reference/materials.md).
  return {shard::PluginKind::Contact, "linear_spring", "1.2.0",
          "linear normal and tangential spring-dashpot with exact restitution and Coulomb friction; effect policy "
          "support_friction (docs/reference/effects.md)",
          std::move(params)};
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_contact(linear_spring_info(), [](const shard::ParamSet& params) {
    return std::make_unique<shard::LinearSpring>(shard::LinearSpring::from(params));
  });
}
