// Test-only bond effect on beam_bond that crashes the process: with bond.segfault_after = N > 0
// its N-th apply() call (one per block of bonds per step) writes through a null pointer, a real
// segmentation fault as a faulty plugin makes one, some steps into the run. The first force pass,
// which the measurement loop's own process makes when it seats the pins on a packing, stays below
// N. At its neutral value 0 the effect is not composed and changes nothing. It exists to show that
// an isolated run pool survives a crashing run (test_isolated_runs); never ship it.
#include <atomic>
#include <memory>

#include "shard/plugin.hpp"

namespace {

class Segfault final : public shard::BondEffect {
 public:
  explicit Segfault(long after) : after_(after) {}
  void initialize(shard::BondEffectBatch&) const override {}
  // Not instrumented by UBSan, which would stop the process at the null store (exit status 1)
  // before the fault; the sanitizer build's test also lets the SIGSEGV through (handle_segv=0,
  // tests/driver/CMakeLists.txt), so the worker dies of the signal there too.
  __attribute__((no_sanitize("undefined"))) void apply(shard::BondEffectBatch&) const override {
    if (after_ <= 0 || ++calls_ < after_) return;
    // A volatile store through a volatile pointer: GCC may neither drop the store nor see the null
    // and turn it into a trap instruction (SIGILL).
    volatile int* volatile target = nullptr;
    *target = 1;
  }

 private:
  long after_;
  mutable std::atomic<long> calls_{0};
};

}  // namespace

SHARD_PLUGIN(registrar) {
  const shard::ParamSpec after{.name = "segfault_after", .unit = "1",
                               .doc = "the apply() call that dies of a segmentation fault; 0 = never",
                               .default_value = 0.0, .min = 0.0, .neutral = 0.0};
  registrar->add_bond_effect(
      {shard::PluginKind::BondEffect, "segfault", "0.1.0", "crashes the run on purpose (tests only)", {after}},
      "beam_bond", [](const shard::ParamSet& params) -> std::unique_ptr<shard::BondEffect> {
        return std::make_unique<Segfault>(static_cast<long>(params.number("segfault_after")));
      });
}
