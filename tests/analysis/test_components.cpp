// Connected components of bond graphs: the Boost.Graph CSR labeller and the union-find labeller
// on graphs with known components, and against each other on random graphs.
#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

#include "graph_fixtures.hpp"

using namespace shard;
using namespace shard::analysis;
using shard::analysis::test::Graph;

namespace {

struct Labelled {
  std::vector<Index> labels;
  Index count = 0;
};

template <class Labeller>
Labelled run(const Graph& g) {
  Labeller labeller;
  Labelled out;
  out.count = labeller.label(g.n, g.bonds(), out.labels);
  return out;
}

// Canonical labels with unit masses and ids = row index.
Labelled canonical(Labelled raw) {
  std::vector<double> mass(raw.labels.size(), 1.0);
  std::vector<Index> id(raw.labels.size());
  std::iota(id.begin(), id.end(), Index{0});
  canonicalise_labels(raw.labels, raw.count, mass, id);
  return raw;
}

// Both labellers, canonicalised, must give exactly the expected labels.
void check_both(const Graph& g, const std::vector<Index>& expected, Index expected_count) {
  const Labelled csr = canonical(run<CsrComponentLabeller>(g));
  const Labelled uf = canonical(run<UnionFindLabeller>(g));
  CHECK(csr.count == expected_count);
  CHECK(uf.count == expected_count);
  CHECK(csr.labels == expected);
  CHECK(uf.labels == expected);
}

}  // namespace

TEST_CASE("a chain is one fragment") {
  const Graph g = test::chain(7);
  check_both(g, std::vector<Index>(7, 0), 1);
}

TEST_CASE("a ring is one fragment, and cutting one bond keeps it whole") {
  Graph ring = test::chain(6);
  ring.bond(5, 0);
  check_both(ring, std::vector<Index>(6, 0), 1);
  // Removing ring bond 2-3 leaves the path 3-4-5-0-1-2: still one piece.
  Graph cut{6, {}, {}};
  for (std::size_t k = 0; k < ring.i.size(); ++k) {
    if (!(ring.i[k] == 2 && ring.j[k] == 3)) cut.bond(ring.i[k], ring.j[k]);
  }
  check_both(cut, std::vector<Index>(6, 0), 1);
}

TEST_CASE("isolated particles and an empty bond set give one fragment per particle") {
  const Graph none{5, {}, {}};
  // Equal masses: ordered by smallest id, so label = row.
  check_both(none, {0, 1, 2, 3, 4}, 5);
  Graph some{5, {}, {}};
  some.bond(3, 1);  // {1,3} weighs 2: fragment 0; singletons 0, 2, 4 follow by id
  check_both(some, {1, 0, 2, 0, 3}, 4);
  const Graph empty{0, {}, {}};
  check_both(empty, {}, 0);
}

TEST_CASE("a grid cut along a line falls into the two sides") {
  // 6 x 4 grid cut between columns 1 and 2: left part 2 columns (8), right part 4 columns (16).
  const Graph g = test::grid_cut(6, 4, 1);
  std::vector<Index> expected(24);
  for (std::size_t k = 0; k < 24; ++k) expected[k] = (k % 6) <= 1 ? 1 : 0;
  check_both(g, expected, 2);
}

TEST_CASE("duplicate bonds and self-bonds do not change the partition") {
  Graph g{4, {}, {}};
  g.bond(0, 1);
  g.bond(1, 0);
  g.bond(2, 2);
  check_both(g, {0, 0, 1, 2}, 3);
}

TEST_CASE("canonical order: heavier first, ties by smallest stable id") {
  // Fragments {0,1} mass 2, {2} mass 3, {3} mass 2; ids reversed so {3} has the smaller id.
  std::vector<Index> labels{0, 0, 1, 2};
  const std::vector<double> mass{1.0, 1.0, 3.0, 2.0};
  const std::vector<Index> id{40, 30, 20, 10};
  canonicalise_labels(labels, 3, mass, id);
  CHECK(labels == std::vector<Index>{2, 2, 0, 1});
}

TEST_CASE("bonds referring to missing particles are rejected") {
  Graph g{3, {}, {}};
  g.bond(0, 3);
  CsrComponentLabeller csr;
  UnionFindLabeller uf;
  std::vector<Index> labels;
  CHECK_THROWS_AS(csr.label(g.n, g.bonds(), labels), std::invalid_argument);
  CHECK_THROWS_AS(uf.label(g.n, g.bonds(), labels), std::invalid_argument);
}

TEST_CASE("the two labellers agree on 1000 random graphs") {
  std::mt19937_64 rng(20240611);
  CsrComponentLabeller csr;  // reused: the in-run mode keeps its buffers across frames
  UnionFindLabeller uf;
  int agreements = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const auto n = std::uniform_int_distribution<std::size_t>(0, 300)(rng);
    // Mean degree from sparse (many fragments) to dense (one), around the percolation threshold.
    const double mean_degree = std::uniform_real_distribution<double>(0.0, 4.0)(rng);
    const auto m = n == 0 ? std::size_t{0} : static_cast<std::size_t>(mean_degree * static_cast<double>(n) / 2.0);
    Graph g{n, {}, {}};
    std::uniform_int_distribution<Index> pick(0, n == 0 ? 0 : static_cast<Index>(n - 1));
    for (std::size_t k = 0; k < m; ++k) g.bond(pick(rng), pick(rng));
    // Random masses and shuffled ids make the canonical order depend on real data.
    std::vector<double> mass(n);
    for (double& x : mass) x = std::uniform_real_distribution<double>(0.5, 2.0)(rng);
    std::vector<Index> id(n);
    std::iota(id.begin(), id.end(), Index{100});
    std::shuffle(id.begin(), id.end(), rng);

    Labelled a, b;
    a.count = csr.label(n, g.bonds(), a.labels);
    b.count = uf.label(n, g.bonds(), b.labels);
    // Raw labels are a valid partition: each bond joins one component.
    for (std::size_t k = 0; k < m; ++k) {
      REQUIRE(a.labels[static_cast<std::size_t>(g.i[k])] == a.labels[static_cast<std::size_t>(g.j[k])]);
      REQUIRE(b.labels[static_cast<std::size_t>(g.i[k])] == b.labels[static_cast<std::size_t>(g.j[k])]);
    }
    canonicalise_labels(a.labels, a.count, mass, id);
    canonicalise_labels(b.labels, b.count, mass, id);
    REQUIRE(a.count == b.count);
    REQUIRE(a.labels == b.labels);
    ++agreements;
  }
  CHECK(agreements == 1000);
}
