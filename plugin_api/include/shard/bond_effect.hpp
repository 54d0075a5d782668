#pragma once
// Out-of-tree bond effects: a policy a plugin adds to a bond law it does not own (e.g. beam_bond)
// without copying the law (docs/how-to/write-a-plugin.md, "A bond effect"). The host composes it onto the law:
//   1. the law computes the batch as usual (its lanes, its state, its breakage);
//   2. each effect on in the scene then runs once over the same batch: it reads the particles and
//      the law's loads, may scale or add to force, torques and energy, and may break a bond.
// An effect keeps its own per-bond state (checkpointed and reordered with the bond, like the
// law's) and never sees the law's, so it does not depend on how the law is written.
// A scene switches an effect on the way it switches a built-in policy on: by naming it in the
// law's `effects` key, or by setting one of its parameters away from its neutral value; its
// parameters sit in the same [bond] table as the law's.
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>

#include "shard/bond_model.hpp"
#include "shard/params.hpp"
#include "shard/time_step.hpp"

namespace shard {

// One sub-batch of bonds as an effect sees it. `bonds` carries the particles, the bond ends and
// (in apply) the law's outputs; its `state` is the law's and is null here. The effect's own
// state: `stride` doubles per bond from `state`, of which it owns the first state_size().
struct BondEffectBatch {
  BondBatch& bonds;
  double* state = nullptr;
  std::size_t stride = 0;
  double* state_of(std::size_t k) const { return state + k * stride; }
};

class BondEffect {
 public:
  virtual ~BondEffect() = default;
  // Doubles of per-bond state this effect keeps (at most kMaxBondEffectState over all effects).
  virtual std::size_t state_size() const { return 0; }
  // At bonding, after the law's own initialize: the effect records what it needs (e.g. l0).
  virtual void initialize(BondEffectBatch& batch) const = 0;
  // Once per step over the batch, after the law: one call per block of bonds, so the loop over
  // bonds inside stays a tight, vectorisable loop (no per-bond virtual call).
  virtual void apply(BondEffectBatch& batch) const = 0;
  // A stricter step than the law's, if the effect adds stiffness; none by default (an effect
  // that only scales loads down or breaks bonds cannot destabilise the law's step).
  virtual std::optional<TimeStepLimit> time_step_limit(const BondEffectBatch&) const { return std::nullopt; }
};

// The sum of state_size() of the effects on in one scene.
inline constexpr std::size_t kMaxBondEffectState = 32;

using BondEffectFactory = std::function<std::unique_ptr<BondEffect>(const ParamSet&)>;

}  // namespace shard
