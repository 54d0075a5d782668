// Lineage: a bar of 12 particles breaks twice; fragments are followed by stable particle id.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <set>

#include "shard/analysis/fragment_table.hpp"
#include "shard/analysis/lineage.hpp"

using namespace shard;
using namespace shard::analysis;

namespace {

constexpr int kBar = 12;

// One frame of the bar: rows in a shuffled order, bonds between consecutive ids except the cut
// ones, bonds given as row indices (as in run.h5).
struct BarFrame {
  std::vector<Index> id;
  std::vector<Vec3> position, velocity;
  std::vector<double> radius, mass;
  std::vector<Index> bond_i, bond_j;
  FragmentAnalysis analysis;

  BarFrame(const std::set<int>& cut_after, unsigned shuffle_seed) {
    for (int k = 0; k < kBar; ++k) id.push_back(k);
    std::mt19937 rng(shuffle_seed);
    std::shuffle(id.begin(), id.end(), rng);
    std::vector<Index> row_of(kBar);
    for (std::size_t row = 0; row < id.size(); ++row) {
      row_of[static_cast<std::size_t>(id[row])] = static_cast<Index>(row);
      position.emplace_back(0.01 * id[row], 0.0, 0.0);
    }
    velocity.assign(kBar, Vec3::Zero());
    radius.assign(kBar, 0.005);
    mass.assign(kBar, 1e-3);
    for (int k = 0; k + 1 < kBar; ++k) {
      if (cut_after.count(k) == 0) {
        bond_i.push_back(row_of[static_cast<std::size_t>(k)]);
        bond_j.push_back(row_of[static_cast<std::size_t>(k + 1)]);
      }
    }
    analysis = analyse_fragments({id, position, velocity, radius, mass, {}}, {bond_i, bond_j});
  }

  LabelledFrame labelled() const {
    return {id, analysis.labels, static_cast<Index>(analysis.fragments.size())};
  }

  std::set<Index> ids_of(Index fragment) const {
    std::set<Index> out;
    for (std::size_t row = 0; row < id.size(); ++row) {
      if (analysis.labels[row] == fragment) out.insert(id[row]);
    }
    return out;
  }
};

std::set<Index> range(Index first, Index last) {
  std::set<Index> out;
  for (Index k = first; k <= last; ++k) out.insert(k);
  return out;
}

}  // namespace

TEST_CASE("a bar breaking twice: (1) -> (2) -> (3) with the right particle sets") {
  const BarFrame intact({}, 1);
  const BarFrame once({3}, 2);      // bond 3-4 broken
  const BarFrame twice({3, 7}, 3);  // and bond 7-8

  REQUIRE(intact.analysis.fragments.size() == 1);
  REQUIRE(once.analysis.fragments.size() == 2);
  REQUIRE(twice.analysis.fragments.size() == 3);
  CHECK(intact.ids_of(0) == range(0, 11));
  // Heavier first: 8 particles, then 4.
  CHECK(once.ids_of(0) == range(4, 11));
  CHECK(once.ids_of(1) == range(0, 3));
  // Equal masses: ordered by smallest id.
  CHECK(twice.ids_of(0) == range(0, 3));
  CHECK(twice.ids_of(1) == range(4, 7));
  CHECK(twice.ids_of(2) == range(8, 11));

  const Lineage first = lineage(intact.labelled(), once.labelled());
  CHECK(first.children.size() == 1);
  CHECK(first.children[0] == std::vector<Index>{0, 1});
  CHECK(first.parent == std::vector<Index>{0, 0});
  REQUIRE(first.overlaps.size() == 2);
  CHECK(first.overlaps[0].shared == 8);
  CHECK(first.overlaps[1].shared == 4);

  const Lineage second = lineage(once.labelled(), twice.labelled());
  REQUIRE(second.children.size() == 2);
  CHECK(second.children[0] == std::vector<Index>{1, 2});  // {4..11} -> {4..7}, {8..11}
  CHECK(second.children[1] == std::vector<Index>{0});     // {0..3} unchanged
  CHECK(second.parent == std::vector<Index>{1, 0, 0});
}

TEST_CASE("a fragment of particles absent from the earlier frame has no parent") {
  const std::vector<Index> id_a{0, 1}, label_a{0, 0};
  const std::vector<Index> id_b{0, 1, 5}, label_b{0, 0, 1};
  const Lineage l = lineage({id_a, label_a, 1}, {id_b, label_b, 2});
  CHECK(l.parent == std::vector<Index>{0, -1});
  CHECK(l.children[0] == std::vector<Index>{0});
}

TEST_CASE("the parent is the fragment sharing most particles") {
  // b0 holds 1 particle of a0 and 2 of a1 (as if re-bonded): parent a1, both overlaps listed.
  const std::vector<Index> id_a{0, 1, 2}, label_a{0, 1, 1};
  const std::vector<Index> id_b{2, 1, 0}, label_b{0, 0, 0};
  const Lineage l = lineage({id_a, label_a, 2}, {id_b, label_b, 1});
  CHECK(l.parent == std::vector<Index>{1});
  REQUIRE(l.overlaps.size() == 2);
  CHECK(l.overlaps[0].a == 0);
  CHECK(l.overlaps[0].shared == 1);
  CHECK(l.overlaps[1].shared == 2);
  CHECK(l.children[0].empty());
}
