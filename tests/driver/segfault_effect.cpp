// Test-only bond effect on beam_bond that crashes the process: with bond.segfault_trigger = 1 its
// first apply() writes through a null pointer (a real segmentation fault, as a faulty plugin
// makes one). At its neutral value 0 it is not composed and changes nothing. It exists to show
// that an isolated run pool survives a crashing run (test_isolated_runs); never ship it.
#include <memory>

#include "shard/plugin.hpp"

namespace {

class Segfault final : public shard::BondEffect {
 public:
  explicit Segfault(bool crash) : crash_(crash) {}
  void initialize(shard::BondEffectBatch&) const override {}
  void apply(shard::BondEffectBatch&) const override {
    if (!crash_) return;
    // Through a volatile pointer: the compiler cannot see the null and turn the store into a trap.
    int* volatile target = nullptr;
    *target = 1;
  }

 private:
  bool crash_;
};

}  // namespace

SHARD_PLUGIN(registrar) {
  const shard::ParamSpec trigger{.name = "segfault_trigger", .unit = "1",
                                 .doc = "1: the first step of the run dies of a segmentation fault", .default_value = 0.0,
                                 .min = 0.0, .max = 1.0, .neutral = 0.0};
  registrar->add_bond_effect(
      {shard::PluginKind::BondEffect, "segfault", "0.1.0", "crashes the run on purpose (tests only)", {trigger}},
      "beam_bond", [](const shard::ParamSet& params) -> std::unique_ptr<shard::BondEffect> {
        return std::make_unique<Segfault>(params.number("segfault_trigger") > 0.5);
      });
}
