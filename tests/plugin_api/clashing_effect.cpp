// A bond effect whose parameter is named like one of beam_bond's own: the host must refuse it,
// whichever of the two loads first (test_bond_effect_host). It is never composed, so it does
// nothing when applied.
#include <memory>
#include <optional>

#include "shard/plugin.hpp"

namespace {

class Clash final : public shard::BondEffect {
 public:
  void initialize(shard::BondEffectBatch&) const override {}
  void apply(shard::BondEffectBatch&) const override {}
};

}  // namespace

SHARD_PLUGIN(registrar) {
  const shard::ParamSpec strength{.name = "critical_stress",  // beam_bond's
                                  .unit = "Pa", .doc = "taken name", .default_value = 1.0, .neutral = std::nullopt};
  registrar->add_bond_effect({shard::PluginKind::BondEffect, "clash", "0.1.0", "clashing parameter name", {strength}},
                             "beam_bond", [](const shard::ParamSet&) -> std::unique_ptr<shard::BondEffect> {
                               return std::make_unique<Clash>();
                             });
}
