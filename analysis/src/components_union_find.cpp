#include "shard/analysis/components.hpp"

// property_map.hpp first: it declares get/put for raw pointers, which disjoint_sets looks up.
#include <boost/property_map/property_map.hpp>
// clang-format off
#include <boost/pending/disjoint_sets.hpp>
// clang-format on

namespace shard::analysis {

Index UnionFindLabeller::label(std::size_t particle_count, const BondList& bonds,
                               std::vector<Index>& labels) {
  check_bonds(particle_count, bonds);
  parent_.resize(particle_count);
  rank_.resize(particle_count);
  // Raw pointers are Boost property maps: no indirection through an index map.
  boost::disjoint_sets<Index*, Index*, boost::find_with_path_halving> sets(rank_.data(),
                                                                           parent_.data());
  for (std::size_t v = 0; v < particle_count; ++v) sets.make_set(static_cast<Index>(v));
  for (std::size_t k = 0; k < bonds.size(); ++k) sets.union_set(bonds.i[k], bonds.j[k]);

  root_label_.assign(particle_count, -1);
  labels.resize(particle_count);
  Index count = 0;
  for (std::size_t v = 0; v < particle_count; ++v) {
    const Index root = sets.find_set(static_cast<Index>(v));
    Index& slot = root_label_[static_cast<std::size_t>(root)];
    if (slot < 0) slot = count++;
    labels[v] = slot;
  }
  return count;
}

}  // namespace shard::analysis
