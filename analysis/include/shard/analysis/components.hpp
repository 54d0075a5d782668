#pragma once
// Fragments are the connected components of the graph whose vertices are particles and whose
// edges are the surviving bonds. Two labellers compute the same partition:
//  - CsrComponentLabeller: Boost.Graph compressed_sparse_row_graph + connected_components, the
//    reference for post-processing a saved frame;
//  - UnionFindLabeller: Boost's disjoint_sets over buffers it keeps between calls, so a running
//    simulation can label every output frame without allocating once warmed up.
// Their raw labels are arbitrary; canonicalise_labels() makes them deterministic.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "shard/types.hpp"

namespace shard::analysis {

// Surviving bonds as two parallel arrays of particle row indices (the kernel's Bonds layout).
struct BondList {
  std::span<const Index> i;
  std::span<const Index> j;
  std::size_t size() const { return i.size(); }
};

// Throws std::invalid_argument if the arrays differ in length or an index is outside [0, n).
void check_bonds(std::size_t particle_count, const BondList& bonds);

class CsrComponentLabeller {
 public:
  // Writes a component label in [0, count) per particle into labels (resized to n) and returns
  // count. Labels are raw: numbered in Boost's DFS discovery order.
  // The graph itself is rebuilt (allocated) on every call.
  Index label(std::size_t particle_count, const BondList& bonds, std::vector<Index>& labels);
};

class UnionFindLabeller {
 public:
  // Same contract as CsrComponentLabeller::label; raw labels are numbered in order of each
  // component's first particle row.
  Index label(std::size_t particle_count, const BondList& bonds, std::vector<Index>& labels);

 private:
  std::vector<Index> parent_, rank_, root_label_;
};

// Renumbers labels in place so that fragment 0 is the heaviest; equal masses are ordered by the
// smallest key (stable particle id) they contain. Fragment masses are summed in particle-row
// order whatever the raw numbering, so two labellings of the same partition give bit-identical
// sums and therefore identical canonical labels.
void canonicalise_labels(std::span<Index> labels, Index count, std::span<const double> mass,
                         std::span<const Index> key);

}  // namespace shard::analysis
