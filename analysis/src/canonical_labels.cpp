#include "shard/analysis/components.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace shard::analysis {

void canonicalise_labels(std::span<Index> labels, Index count, std::span<const double> mass,
                         std::span<const Index> key) {
  if (mass.size() != labels.size() || key.size() != labels.size()) {
    throw std::invalid_argument("canonicalise_labels: labels, mass and key differ in length");
  }
  const auto fragments = static_cast<std::size_t>(count);
  std::vector<double> fragment_mass(fragments, 0.0);
  std::vector<Index> smallest_key(fragments, std::numeric_limits<Index>::max());
  for (std::size_t v = 0; v < labels.size(); ++v) {
    const auto f = static_cast<std::size_t>(labels[v]);
    if (labels[v] < 0 || f >= fragments) {
      throw std::invalid_argument("canonicalise_labels: label outside [0, count)");
    }
    fragment_mass[f] += mass[v];
    smallest_key[f] = std::min(smallest_key[f], key[v]);
  }
  std::vector<Index> order(fragments);
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    if (fragment_mass[ua] != fragment_mass[ub]) return fragment_mass[ua] > fragment_mass[ub];
    return smallest_key[ua] < smallest_key[ub];
  });
  std::vector<Index> new_label(fragments);
  for (std::size_t rank = 0; rank < fragments; ++rank) {
    new_label[static_cast<std::size_t>(order[rank])] = static_cast<Index>(rank);
  }
  for (auto& l : labels) l = new_label[static_cast<std::size_t>(l)];
}

}  // namespace shard::analysis
