#include "composed_bond.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace shard {
namespace {

// Copies the law's and the effects' parts of `count` interleaved bond states apart.
void unpack(const double* state, std::size_t count, std::size_t law_size, std::size_t effect_size, double* law,
            double* effects) {
  const std::size_t stride = law_size + effect_size;
  for (std::size_t k = 0; k < count; ++k) {
    std::copy_n(state + k * stride, law_size, law + k * law_size);
    std::copy_n(state + k * stride + law_size, effect_size, effects + k * effect_size);
  }
}

void pack(const double* law, const double* effects, std::size_t count, std::size_t law_size, std::size_t effect_size,
          double* state) {
  const std::size_t stride = law_size + effect_size;
  for (std::size_t k = 0; k < count; ++k) {
    std::copy_n(law + k * law_size, law_size, state + k * stride);
    std::copy_n(effects + k * effect_size, effect_size, state + k * stride + law_size);
  }
}

// The batch as an effect sees it: everything but the law's state.
BondBatch without_state(const BondBatch& batch) {
  BondBatch view = batch;
  view.state = nullptr;
  return view;
}

}  // namespace

ComposedBond::ComposedBond(std::unique_ptr<BondModel> law, std::vector<std::unique_ptr<BondEffect>> effects)
    : law_(std::move(law)), effects_(std::move(effects)), law_size_(law_->state_size()) {
  for (const auto& effect : effects_) {
    offsets_.push_back(effect_size_);
    effect_size_ += effect->state_size();
  }
  if (effect_size_ > kMaxBondEffectState)
    throw std::invalid_argument(fmt::format("the bond effects of this scene keep {} doubles of state per bond; "
                                            "at most {} fit (kMaxBondEffectState, shard/bond_effect.hpp)",
                                            effect_size_, kMaxBondEffectState));
}

void ComposedBond::initialize(BondBatch& batch) const {
  std::vector<double> law_state(batch.count * law_size_), effect_state(batch.count * effect_size_);
  BondBatch law_batch = batch;
  law_batch.state = law_state.data();
  law_->initialize(law_batch);
  BondBatch view = without_state(batch);
  for (std::size_t e = 0; e < effects_.size(); ++e) {
    BondEffectBatch effect_batch{view, effect_state.data() + offsets_[e], effect_size_};
    effects_[e]->initialize(effect_batch);
  }
  pack(law_state.data(), effect_state.data(), batch.count, law_size_, effect_size_, batch.state);
}

TimeStepLimit ComposedBond::time_step_limit(const BondBatch& batch) const {
  std::vector<double> law_state(batch.count * law_size_), effect_state(batch.count * effect_size_);
  unpack(batch.state, batch.count, law_size_, effect_size_, law_state.data(), effect_state.data());
  BondBatch law_batch = batch;
  law_batch.state = law_state.data();
  TimeStepLimit limit = law_->time_step_limit(law_batch);
  BondBatch view = without_state(batch);
  for (std::size_t e = 0; e < effects_.size(); ++e) {
    const BondEffectBatch effect_batch{view, effect_state.data() + offsets_[e], effect_size_};
    const auto own = effects_[e]->time_step_limit(effect_batch);
    if (own && own->recommended < limit.recommended) limit = *own;
  }
  return limit;
}

void ComposedBond::compute(BondBatch& batch) const {
  for (std::size_t first = 0; first < batch.count; first += kBlock) {
    BondBatch block = batch;
    block.count = std::min(kBlock, batch.count - first);
    block.i += first;
    block.j += first;
    block.state += first * state_size();
    block.force += first;
    block.torque_i += first;
    block.torque_j += first;
    block.energy += first;
    block.broken += first;
    block.stress += first;
    compute_block(block);
  }
}

// Copies a bond's few doubles in place; the ranges of one bond may overlap, so forward when the
// destination lies before the source and backward when after.
inline void copy_forward(const double* from, std::size_t n, double* to) {
  for (std::size_t s = 0; s < n; ++s) to[s] = from[s];
}
inline void copy_backward(const double* from, std::size_t n, double* to) {
  for (std::size_t s = n; s-- > 0;) to[s] = from[s];
}

void ComposedBond::compute_block(BondBatch& batch) const {
  const std::size_t n = batch.count, stride = state_size();
  double effect_state[kBlock * kMaxBondEffectState];
  double* state = batch.state;
  if (effect_size_ > 0) {
    // Effects' parts aside, then the law's packed at its own stride; forward, as each bond's
    // packed place starts at or before its interleaved one.
    for (std::size_t k = 0; k < n; ++k)
      copy_forward(state + k * stride + law_size_, effect_size_, effect_state + k * effect_size_);
    for (std::size_t k = 1; k < n; ++k) copy_forward(state + k * stride, law_size_, state + k * law_size_);
  }
  law_->compute(batch);
  if (effect_size_ > 0)  // back to the interleaved layout, last bond first for the same reason
    for (std::size_t k = n; k-- > 1;) copy_backward(state + k * law_size_, law_size_, state + k * stride);
  BondBatch view = without_state(batch);
  for (std::size_t e = 0; e < effects_.size(); ++e) {
    BondEffectBatch effect_batch{view, effect_state + offsets_[e], effect_size_};
    effects_[e]->apply(effect_batch);
  }
  if (effect_size_ > 0)
    for (std::size_t k = 0; k < n; ++k)
      copy_forward(effect_state + k * effect_size_, effect_size_, state + k * stride + law_size_);
}

}  // namespace shard
