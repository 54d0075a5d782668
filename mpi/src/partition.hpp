#pragma once
// The space-filling-curve partition of a decomposed run: the neighbour-cell grid's non-empty cells
// in Morton (Z) order, cut into one contiguous key range per rank of about equal cost (particles +
// bonds + contacts of each cell). Contiguous key ranges are compact sub-domains; re-balancing at
// a rebuild only moves the range ends. Pure arithmetic, no MPI: every rank computes the same
// partition from the same gathered cell costs.
#include <array>
#include <cstdint>
#include <vector>

#include "shard/types.hpp"

namespace shard::mpi {

struct CellCost {
  std::uint64_t key = 0;
  double cost = 0;
};

// The grid: cubes of `cell` metres from `origin`, coordinates 0 .. 2^21 - 1 per axis.
struct CellGrid {
  Vec3 origin = Vec3::Zero();
  double cell = 1;
  std::array<std::int64_t, 3> coords(const Vec3& x) const;
  std::uint64_t key(const Vec3& x) const;
};

std::uint64_t morton_key(std::int64_t x, std::int64_t y, std::int64_t z);
std::array<std::int64_t, 3> morton_coords(std::uint64_t key);

class Partition {
 public:
  // `cells` from every rank (a cell may appear more than once, its costs are added), cut into
  // `ranks` ranges. Throws std::invalid_argument when some rank would get no cell.
  static Partition balance(std::vector<CellCost> cells, int ranks, double cell_size);

  // The rank owning the cell of `key`; -1 for a cell that held no particle at the partition.
  int owner_of(std::uint64_t key) const;
  // The ranks other than `self` owning one of the 26 cells around `key` (ascending, no repeats).
  void neighbour_ranks(std::uint64_t key, int self, std::vector<int>& out) const;
  std::size_t cells() const { return keys_.size(); }
  double cost_of(int rank) const { return cost_[static_cast<std::size_t>(rank)]; }

 private:
  std::vector<std::uint64_t> keys_;  // ascending
  std::vector<int> owner_;
  std::vector<double> cost_;  // per rank
  // The owners over the cells' bounding box, when it is not much larger than the cells themselves
  // (a solid block): a ghost search looks up 26 neighbours per cell, a search each otherwise.
  std::array<std::int64_t, 3> box_lo_{}, box_size_{};
  std::vector<int> dense_;
};

}  // namespace shard::mpi
