#pragma once
// Small graphs whose components are known by construction.
#include <cstddef>
#include <vector>

#include "shard/analysis/components.hpp"

namespace shard::analysis::test {

struct Graph {
  std::size_t n = 0;
  std::vector<Index> i, j;
  void bond(Index a, Index b) {
    i.push_back(a);
    j.push_back(b);
  }
  BondList bonds() const { return {i, j}; }
};

// A path 0-1-...-(n-1).
inline Graph chain(std::size_t n) {
  Graph g{n, {}, {}};
  for (std::size_t k = 0; k + 1 < n; ++k) g.bond(static_cast<Index>(k), static_cast<Index>(k + 1));
  return g;
}

// nx by ny grid, row-major (index = x + nx*y), 4-neighbour bonds; the bonds crossing between
// columns cut_x and cut_x+1 are left out so the grid falls in two pieces.
inline Graph grid_cut(std::size_t nx, std::size_t ny, std::size_t cut_x) {
  Graph g{nx * ny, {}, {}};
  auto at = [nx](std::size_t x, std::size_t y) { return static_cast<Index>(x + nx * y); };
  for (std::size_t y = 0; y < ny; ++y) {
    for (std::size_t x = 0; x < nx; ++x) {
      if (x + 1 < nx && x != cut_x) g.bond(at(x, y), at(x + 1, y));
      if (y + 1 < ny) g.bond(at(x, y), at(x, y + 1));
    }
  }
  return g;
}

}  // namespace shard::analysis::test
