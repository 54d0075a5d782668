#include "partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shard::mpi {
namespace {

constexpr std::int64_t kAxisCells = std::int64_t{1} << 21;

// Bits of v spread to every third bit.
std::uint64_t spread(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffff;
  v = (v | v << 16) & 0x1f0000ff0000ff;
  v = (v | v << 8) & 0x100f00f00f00f00f;
  v = (v | v << 4) & 0x10c30c30c30c30c3;
  v = (v | v << 2) & 0x1249249249249249;
  return v;
}

std::uint64_t gather(std::uint64_t v) {
  v &= 0x1249249249249249;
  v = (v | v >> 2) & 0x10c30c30c30c30c3;
  v = (v | v >> 4) & 0x100f00f00f00f00f;
  v = (v | v >> 8) & 0x1f0000ff0000ff;
  v = (v | v >> 16) & 0x1f00000000ffff;
  v = (v | v >> 32) & 0x1fffff;
  return v;
}

}  // namespace

std::uint64_t morton_key(std::int64_t x, std::int64_t y, std::int64_t z) {
  return spread(static_cast<std::uint64_t>(x)) | spread(static_cast<std::uint64_t>(y)) << 1 |
         spread(static_cast<std::uint64_t>(z)) << 2;
}

std::array<std::int64_t, 3> morton_coords(std::uint64_t key) {
  return {static_cast<std::int64_t>(gather(key)), static_cast<std::int64_t>(gather(key >> 1)),
          static_cast<std::int64_t>(gather(key >> 2))};
}

std::array<std::int64_t, 3> CellGrid::coords(const Vec3& x) const {
  std::array<std::int64_t, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double u = std::floor((x[a] - origin[a]) / cell);
    if (!(u >= 0 && u < static_cast<double>(kAxisCells)))
      throw std::runtime_error(fmt::format(
          "a particle at ({}, {}, {}) m lies outside the partition grid ({} cells of {} m per axis): a particle "
          "has escaped or its position is not finite (the run has blown up)",
          x.x(), x.y(), x.z(), kAxisCells, cell));
    c[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(u);
  }
  return c;
}

std::uint64_t CellGrid::key(const Vec3& x) const {
  const auto c = coords(x);
  return morton_key(c[0], c[1], c[2]);
}

Partition Partition::balance(std::vector<CellCost> cells, int ranks, double cell_size) {
  std::stable_sort(cells.begin(), cells.end(), [](const CellCost& a, const CellCost& b) { return a.key < b.key; });
  Partition p;
  std::vector<double> cost;
  for (const CellCost& c : cells) {
    if (!p.keys_.empty() && p.keys_.back() == c.key) {
      cost.back() += c.cost;
    } else {
      p.keys_.push_back(c.key);
      cost.push_back(c.cost);
    }
  }
  double total = 0;
  for (double c : cost) total += c;
  // Cell c goes to the rank whose share of the total cost holds the middle of c's cost.
  p.owner_.resize(p.keys_.size());
  p.cost_.assign(static_cast<std::size_t>(ranks), 0.0);
  std::vector<std::size_t> count(static_cast<std::size_t>(ranks), 0);
  double before = 0;
  for (std::size_t k = 0; k < cost.size(); ++k) {
    const double middle = (before + 0.5 * cost[k]) / total * ranks;
    const int r = std::clamp(static_cast<int>(middle), 0, ranks - 1);
    p.owner_[k] = r;
    p.cost_[static_cast<std::size_t>(r)] += cost[k];
    ++count[static_cast<std::size_t>(r)];
    before += cost[k];
  }
  std::array<std::int64_t, 3> lo{kAxisCells, kAxisCells, kAxisCells}, hi{0, 0, 0};
  for (std::uint64_t key : p.keys_) {
    const auto c = morton_coords(key);
    for (std::size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], c[a]);
      hi[a] = std::max(hi[a], c[a]);
    }
  }
  const double box = static_cast<double>(hi[0] - lo[0] + 1) * static_cast<double>(hi[1] - lo[1] + 1) *
                     static_cast<double>(hi[2] - lo[2] + 1);
  if (!p.keys_.empty() && box <= 8.0 * static_cast<double>(p.keys_.size()) + 4096) {
    p.box_lo_ = lo;
    for (std::size_t a = 0; a < 3; ++a) p.box_size_[a] = hi[a] - lo[a] + 1;
    p.dense_.assign(static_cast<std::size_t>(box), -1);
    for (std::size_t k = 0; k < p.keys_.size(); ++k) {
      const auto c = morton_coords(p.keys_[k]);
      p.dense_[static_cast<std::size_t>(((c[2] - lo[2]) * p.box_size_[1] + (c[1] - lo[1])) * p.box_size_[0] + (c[0] - lo[0]))] =
          p.owner_[k];
    }
  }
  for (int r = 0; r < ranks; ++r)
    if (count[static_cast<std::size_t>(r)] == 0)
      throw std::invalid_argument(fmt::format(
          "{} MPI ranks cannot hold a partition of this scene: it fills only {} neighbour cell(s) of {:.4g} m, and "
          "the cost-balanced ranges leave rank {} without a cell; run on fewer ranks (at most {}, fewer when a few "
          "cells carry most of the particles, bonds and contacts)",
          ranks, p.keys_.size(), cell_size, r, p.keys_.size()));
  return p;
}

int Partition::owner_of(std::uint64_t key) const {
  const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  if (it == keys_.end() || *it != key) return -1;
  return owner_[static_cast<std::size_t>(it - keys_.begin())];
}

void Partition::neighbour_ranks(std::uint64_t key, int self, std::vector<int>& out) const {
  out.clear();
  const auto c = morton_coords(key);
  for (std::int64_t dz = -1; dz <= 1; ++dz)
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const std::int64_t x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
        if (x < 0 || y < 0 || z < 0 || x >= kAxisCells || y >= kAxisCells || z >= kAxisCells) continue;
        int r = -1;
        if (!dense_.empty()) {
          const std::int64_t u = x - box_lo_[0], v = y - box_lo_[1], w = z - box_lo_[2];
          if (u >= 0 && v >= 0 && w >= 0 && u < box_size_[0] && v < box_size_[1] && w < box_size_[2])
            r = dense_[static_cast<std::size_t>((w * box_size_[1] + v) * box_size_[0] + u)];
        } else {
          r = owner_of(morton_key(x, y, z));
        }
        if (r >= 0 && r != self) out.push_back(r);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace shard::mpi
