#include "shard/analysis/lineage.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

namespace shard::analysis {

namespace {
void check_frame(const LabelledFrame& f, const char* name) {
  if (f.id.size() != f.label.size()) {
    throw std::invalid_argument(std::string("lineage: frame ") + name +
                                " has ids and labels of different lengths");
  }
  for (Index l : f.label) {
    if (l < 0 || l >= f.count) {
      throw std::invalid_argument(std::string("lineage: frame ") + name + " has a label outside [0, " +
                                  std::to_string(f.count) + ")");
    }
  }
}
}  // namespace

Lineage lineage(const LabelledFrame& a, const LabelledFrame& b) {
  check_frame(a, "A");
  check_frame(b, "B");
  std::unordered_map<Index, Index> label_in_a;
  label_in_a.reserve(a.id.size());
  for (std::size_t v = 0; v < a.id.size(); ++v) {
    if (!label_in_a.emplace(a.id[v], a.label[v]).second) {
      throw std::invalid_argument("lineage: frame A repeats particle id " + std::to_string(a.id[v]));
    }
  }
  // Count shared particles per (a, b) pair; pairs are few (about one per fragment of B).
  std::vector<std::pair<Index, Index>> pairs;  // (a, b) per particle of B found in A
  pairs.reserve(b.id.size());
  for (std::size_t v = 0; v < b.id.size(); ++v) {
    const auto it = label_in_a.find(b.id[v]);
    if (it != label_in_a.end()) pairs.emplace_back(it->second, b.label[v]);
  }
  std::sort(pairs.begin(), pairs.end());
  Lineage result;
  for (std::size_t k = 0; k < pairs.size();) {
    std::size_t end = k;
    while (end < pairs.size() && pairs[end] == pairs[k]) ++end;
    result.overlaps.push_back({pairs[k].first, pairs[k].second, end - k});
    k = end;
  }
  result.parent.assign(static_cast<std::size_t>(b.count), -1);
  std::vector<std::size_t> best_shared(static_cast<std::size_t>(b.count), 0);
  for (const Overlap& o : result.overlaps) {  // ascending a: a strict '>' keeps the smaller a on ties
    const auto ub = static_cast<std::size_t>(o.b);
    if (o.shared > best_shared[ub]) {
      best_shared[ub] = o.shared;
      result.parent[ub] = o.a;
    }
  }
  result.children.assign(static_cast<std::size_t>(a.count), {});
  for (std::size_t ub = 0; ub < result.parent.size(); ++ub) {
    if (result.parent[ub] >= 0) {
      result.children[static_cast<std::size_t>(result.parent[ub])].push_back(static_cast<Index>(ub));
    }
  }
  return result;
}

}  // namespace shard::analysis
