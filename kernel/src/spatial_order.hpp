#pragma once
// Renumbering particles along a space-filling curve (Morton / Z order) so that particles close in
// space are close in memory: the pair and bond loops then read particle data that is already in
// cache. Bonds follow the particles and are re-sorted by their smaller index.
#include <cstdint>
#include <utility>
#include <vector>

#include "shard/bonds.hpp"
#include "shard/particles.hpp"

namespace shard {

class SpatialOrder {
 public:
  // Computes the Morton order of the particles on a grid of `cell` (m). Returns false when the
  // particles are already in that order (nothing to do).
  bool compute(const Particles& particles, double cell);
  // new_index()[old] = new, after compute().
  const std::vector<Index>& new_index() const { return new_index_; }
  // Applies the order: particle arrays permuted, bond ends renamed and bonds sorted by their
  // smaller end (stable), bond state moved with its bond.
  void apply(Particles& particles, Bonds& bonds);

 private:
  std::vector<std::pair<std::uint64_t, Index>> keys_;
  std::vector<Index> order_;      // order_[new] = old
  std::vector<Index> new_index_;  // inverse
  // Scratch arrays swapped with the live ones, so a reordering does not allocate once warmed up.
  Particles scratch_;
  Bonds bond_scratch_;
  std::vector<std::int64_t> bond_start_;
  std::vector<std::size_t> bond_order_;
  bool live_on_huge_pages_ = false;  // a reordering has put the live arrays on advised storage
};

}  // namespace shard
