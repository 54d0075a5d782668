#pragma once
// A bond law with out-of-tree effects composed onto it (shard/bond_effect.hpp). Each bond's
// state in the kernel's array is the law's, then the effects' in order:
//   [ law: law.state_size() | effect 1 | effect 2 | ... ]
// The law reads its state at its own stride, so for each block of bonds the composition moves the
// effects' part aside (onto the stack), packs the law's part, runs the law, unpacks it, and runs
// the effects on their part: the law is called unchanged, at its own lane speed, and no heap
// memory is touched in the step.
#include <cstddef>
#include <memory>
#include <vector>

#include "shard/bond_effect.hpp"
#include "shard/bond_model.hpp"

namespace shard {

class ComposedBond final : public BondModel {
 public:
  // Throws std::invalid_argument when the effects' state exceeds kMaxBondEffectState.
  ComposedBond(std::unique_ptr<BondModel> law, std::vector<std::unique_ptr<BondEffect>> effects);

  std::size_t state_size() const override { return law_size_ + effect_size_; }
  void initialize(BondBatch& batch) const override;
  TimeStepLimit time_step_limit(const BondBatch& batch) const override;
  void compute(BondBatch& batch) const override;
  bool writes_every_output() const override { return law_->writes_every_output(); }

 private:
  // Bonds per block of compute(): the stack holds kBlock * kMaxBondEffectState doubles.
  static constexpr std::size_t kBlock = 64;
  void compute_block(BondBatch& batch) const;

  std::unique_ptr<BondModel> law_;
  std::vector<std::unique_ptr<BondEffect>> effects_;
  std::vector<std::size_t> offsets_;  // each effect's first double in the effects' part
  std::size_t law_size_ = 0, effect_size_ = 0;
};

}  // namespace shard
