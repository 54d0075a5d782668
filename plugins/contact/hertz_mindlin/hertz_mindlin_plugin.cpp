// Registration of the hertz_mindlin contact model: its name, version and parameter schema.
#include <memory>
#include <optional>

#include "hertz_mindlin_model.hpp"
#include "shard/plugin.hpp"

namespace {

shard::PluginInfo hertz_mindlin_info() {
  using shard::ParamSpec;
  const shard::HertzMindlinMaterial defaults;
  ParamSpec shear{.name = "shear_modulus",
                  .unit = "Pa",
                  .doc = "shear modulus G of the particles (walls are taken of the same material)",
                  .default_value = defaults.shear_modulus,
                  .min = 0.0,
                  .min_exclusive = true,
                  .neutral = std::nullopt};
  ParamSpec poisson{.name = "poisson_ratio",
                    .unit = "1",
                    .doc = "Poisson's ratio nu (not given in the seed; 0.25 is common)",
                    .default_value = defaults.poisson_ratio,
                    .min = -1.0,
                    .max = 0.5,
                    .min_exclusive = true,
                    .neutral = std::nullopt};
  ParamSpec friction{.name = "friction",
                     .unit = "1",
                     .doc = "Coulomb sliding friction coefficient mu, |F_t| <= mu F_n",
                     .default_value = defaults.friction,
                     .min = 0.0,
                     .max = 10.0,
                     .neutral = 0.0};
  ParamSpec restitution{.name = "restitution",
                        .unit = "1",
                        .doc = "normal coefficient of restitution e, realised exactly for any impact speed",
                        .default_value = defaults.restitution,
                        .min = 0.0,
                        .max = 1.0,
                        .min_exclusive = true,
                        .neutral = 1.0};
  return {shard::PluginKind::Contact, "hertz_mindlin", "1.0.0",
          "Hertz normal and Mindlin tangential spring with restitution damping and Coulomb friction",
          {shear, poisson, friction, restitution}};
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_contact(hertz_mindlin_info(), [](const shard::ParamSet& params) {
    return std::make_unique<shard::HertzMindlin>(shard::HertzMindlinMaterial::from(params));
  });
}
