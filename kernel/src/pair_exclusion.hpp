#pragma once
// Particle pairs the neighbour list leaves out: with [simulation] bonded_contacts = false, the
// pairs joined by an intact bond, which then feel their bond alone (as LAMMPS' BPM package does);
// a pair's contact starts at the rebuild that follows its bond's failure.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "shard/particles.hpp"

namespace shard {

class PairExclusion {
 public:
  // The pairs (i[k], j[k]) among `particles` particles, grouped by their smaller index.
  void assign(const std::vector<Index>& i, const std::vector<Index>& j, std::size_t particles) {
    start_.assign(particles + 1, 0);
    for (std::size_t k = 0; k < i.size(); ++k) ++start_[static_cast<std::size_t>(std::min(i[k], j[k])) + 1];
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    cursor_.assign(start_.begin(), start_.end() - 1);
    partner_.resize(i.size());
    for (std::size_t k = 0; k < i.size(); ++k)
      partner_[static_cast<std::size_t>(cursor_[static_cast<std::size_t>(std::min(i[k], j[k]))]++)] =
          std::max(i[k], j[k]);
  }
  // Whether (a, b), a < b, is left out: a scan of a's dozen partners at most.
  bool contains(Index a, Index b) const {
    const auto from = partner_.begin() + start_[static_cast<std::size_t>(a)];
    const auto to = partner_.begin() + start_[static_cast<std::size_t>(a) + 1];
    return std::find(from, to, b) != to;
  }

 private:
  std::vector<std::int64_t> start_, cursor_;
  std::vector<Index> partner_;
};

}  // namespace shard
