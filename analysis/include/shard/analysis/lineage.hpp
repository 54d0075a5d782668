#pragma once
// Lineage between two analysed frames A (earlier) and B (later): which fragment of A became which
// fragments of B, found by the particles they share (stable ids survive reordering).
//
// Rule: fragment b of B descends from the fragment a of A that holds the largest number of b's
// particles (ties: the smaller label a, i.e. the heavier one under canonical numbering). A
// particle of B absent from A (inserted later) links to nothing; b has no parent (-1) if none of
// its particles existed in A. Every overlap is also listed, so a fragment merging pieces of two
// parents (re-bonding, not modelled by Shard) would still be visible.
#include <cstddef>
#include <span>
#include <vector>

#include "shard/types.hpp"

namespace shard::analysis {

struct LabelledFrame {
  std::span<const Index> id;      // stable particle id per row
  std::span<const Index> label;   // fragment label per row, in [0, count)
  Index count = 0;
};

struct Overlap {
  Index a = 0, b = 0;            // fragment of frame A, fragment of frame B
  std::size_t shared = 0;        // particles present in both
};

struct Lineage {
  std::vector<Overlap> overlaps;            // sorted by (a, b)
  std::vector<Index> parent;                // per fragment of B: its fragment of A, or -1
  std::vector<std::vector<Index>> children; // per fragment of A: fragments of B whose parent it is
};

Lineage lineage(const LabelledFrame& a, const LabelledFrame& b);

}  // namespace shard::analysis
