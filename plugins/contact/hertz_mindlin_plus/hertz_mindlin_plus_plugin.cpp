// Registers hertz_mindlin_plus: hertz_mindlin's parameters (same names, units, defaults) plus
// wall friction and contact cohesion, each with its neutral value.
#include <memory>
#include <optional>

#include "../common/contact_params.hpp"
#include "hertz_mindlin_plus_model.hpp"
#include "shard/plugin.hpp"

namespace {

shard::PluginInfo hertz_mindlin_plus_info() {
  using shard::ParamSpec;
  const shard::hertz_plus::HertzMindlinPlusParams d;
  namespace cp = shard::contact_params;
  const ParamSpec shear = cp::shear_modulus(d.shear_modulus);
  const ParamSpec poisson = cp::poisson_ratio(d.poisson_ratio);
  const ParamSpec friction = cp::friction(d.friction);
  const ParamSpec restitution = cp::restitution(d.restitution);
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
