// Registers hertz_mindlin_plus: hertz_mindlin's parameters (same names, units, defaults) plus
// wall friction and contact cohesion, each with its neutral value.
#include <memory>
#include <optional>

#include "hertz_mindlin_plus_model.hpp"
#include "shard/plugin.hpp"

namespace {

shard::PluginInfo hertz_mindlin_plus_info() {
  using shard::ParamSpec;
  const shard::hertz_plus::HertzMindlinPlusParams d;
  ParamSpec shear{.name = "shear_modulus", .unit = "Pa",
                  .doc = "shear modulus G of the particles (walls are taken of the same material)",
                  .default_value = d.shear_modulus, .min = 0.0, .min_exclusive = true, .neutral = std::nullopt};
  ParamSpec poisson{.name = "poisson_ratio", .unit = "1", .doc = "Poisson's ratio nu",
                    .default_value = d.poisson_ratio, .min = -1.0, .max = 0.5, .min_exclusive = true,
                    .neutral = std::nullopt};
  ParamSpec friction{.name = "friction", .unit = "1", .doc = "Coulomb friction between particles, |F_t| <= mu F_n",
                     .default_value = d.friction, .min = 0.0, .max = 10.0, .neutral = 0.0};
  ParamSpec restitution{.name = "restitution", .unit = "1", .doc = "normal coefficient of restitution e",
                        .default_value = d.restitution, .min = 0.0, .max = 1.0, .min_exclusive = true,
                        .neutral = 1.0};
  ParamSpec wall{.name = "wall_friction", .unit = "1",
                 .doc = "Coulomb friction at particle-wall contacts (supports, pins); -1 = same as friction",
                 .default_value = d.wall_friction, .min = -1.0, .max = 10.0, .neutral = -1.0};
  ParamSpec cohesion{.name = "cohesion_stress", .unit = "Pa",
                     .doc = "pull per contact area pi R* delta between touching particles (linear cohesion); 0 = none",
                     .default_value = d.cohesion_stress, .min = 0.0, .neutral = 0.0};
  return {shard::PluginKind::Contact, "hertz_mindlin_plus", "1.0.0",
          "hertz_mindlin + friction of its own at walls, cohesive pull per contact area (docs/effects.md)",
          {shear, poisson, friction, restitution, wall, cohesion}};
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_contact(hertz_mindlin_plus_info(), [](const shard::ParamSet& params) {
    return std::make_unique<shard::hertz_plus::HertzMindlinPlus>(shard::hertz_plus::HertzMindlinPlusParams::from(params));
  });
}
