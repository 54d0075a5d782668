#pragma once
// Uniform cell grid over sphere centres for O(1) neighbourhood queries while a packing grows.
// Cells are linked lists in two flat arrays (head per cell, next per sphere): inserting never
// allocates per cell. Points outside the box are kept in the border cells, so queries stay exact.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "shard/types.hpp"

namespace shard::geometry {

class SphereGrid {
 public:
  SphereGrid(const Vec3& lower, const Vec3& upper, double cell_size) : lower_(lower), cell_(cell_size) {
    if (!(cell_size > 0.0)) throw std::invalid_argument("SphereGrid: cell size must be > 0");
    std::int64_t total = 1;
    for (int k = 0; k < 3; ++k) {
      dims_[k] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((upper[k] - lower[k]) / cell_)));
      total *= dims_[k];
    }
    if (total > (std::int64_t{1} << 31))
      throw std::invalid_argument("SphereGrid: more than 2^31 cells; the body is too large for this diameter");
    head_.assign(static_cast<std::size_t>(total), -1);
  }

  void insert(Index id, const Vec3& centre) {
    if (static_cast<std::size_t>(id) >= next_.size()) next_.resize(static_cast<std::size_t>(id) + 1, -1);
    const std::size_t c = cell_of(centre);
    next_[static_cast<std::size_t>(id)] = head_[c];
    head_[c] = id;
  }

  // Calls visit(id) for every sphere whose centre may lie within `reach` of p (a superset).
  // visit returns false to stop early; for_each_near then returns false too.
  template <class Visit>
  bool for_each_near(const Vec3& p, double reach, Visit&& visit) const {
    std::int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = clamp_index(static_cast<std::int64_t>(std::floor((p[k] - reach - lower_[k]) / cell_)), k);
      hi[k] = clamp_index(static_cast<std::int64_t>(std::floor((p[k] + reach - lower_[k]) / cell_)), k);
    }
    for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
          for (Index id = head_[flat(i, j, k)]; id >= 0; id = next_[static_cast<std::size_t>(id)])
            if (!visit(id)) return false;
    return true;
  }

 private:
  std::int64_t clamp_index(std::int64_t i, int axis) const { return std::clamp<std::int64_t>(i, 0, dims_[axis] - 1); }
  std::size_t flat(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<std::size_t>((k * dims_[1] + j) * dims_[0] + i);
  }
  std::size_t cell_of(const Vec3& p) const {
    std::int64_t idx[3];
    for (int k = 0; k < 3; ++k) idx[k] = clamp_index(static_cast<std::int64_t>(std::floor((p[k] - lower_[k]) / cell_)), k);
    return flat(idx[0], idx[1], idx[2]);
  }

  Vec3 lower_;
  double cell_;
  std::int64_t dims_[3] = {1, 1, 1};
  std::vector<Index> head_;
  std::vector<Index> next_;
};

}  // namespace shard::geometry
