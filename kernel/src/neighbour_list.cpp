#include "neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace shard {

NeighbourList::NeighbourList(double skin, std::size_t history_stride) : skin_(skin), stride_(history_stride) {}

bool NeighbourList::update(const Particles& particles, const std::vector<Wall>& walls) {
  if (position_at_build_.size() == particles.size() && !needs_rebuild(particles, walls)) return false;
  rebuild(particles, walls);
  return true;
}

bool NeighbourList::needs_rebuild(const Particles& particles, const std::vector<Wall>& walls) const {
  double max_particle = 0;
  const std::size_t n = particles.size();
  for (std::size_t k = 0; k < n; ++k)
    max_particle = std::max(max_particle, (particles.position[k] - position_at_build_[k]).squaredNorm());
  max_particle = std::sqrt(max_particle);
  double max_wall = 0;
  for (std::size_t w = 0; w < walls.size(); ++w)
    max_wall = std::max(max_wall, (walls[w].displacement - wall_displacement_at_build_[w]).norm());
  // Two particles approach each other by at most twice the largest displacement.
  return 2 * max_particle > skin_ || max_particle + max_wall > skin_;
}

void NeighbourList::rebuild(const Particles& particles, const std::vector<Wall>& walls) {
  ++rebuilds_;
  const std::size_t n = particles.size();
  new_i_.clear();
  new_j_.clear();
  new_history_.clear();
  if (n > 0) {
    double r_max = 0;
    Vec3 lo = particles.position[0], hi = particles.position[0];
    for (std::size_t k = 0; k < n; ++k) {
      r_max = std::max(r_max, particles.radius[k]);
      lo = lo.cwiseMin(particles.position[k]);
      hi = hi.cwiseMax(particles.position[k]);
    }
    double cell = 2 * r_max + skin_;
    // Keep the grid at most a few cells per particle, however far the particles spread.
    Eigen::Array3d extent = (hi - lo).array() + cell;
    auto cells_for = [&](double c) {
      return ((extent / c).ceil()).cast<double>().prod();
    };
    while (cells_for(cell) > 8.0 * static_cast<double>(n) + 64) cell *= 1.5;
    const Eigen::Array3i dims = (extent / cell).ceil().cast<int>().max(1);
    const auto cell_index = [&](const Vec3& x, Eigen::Array3i& c) {
      c = ((x - lo).array() / cell).floor().cast<int>().min(dims - 1).max(0);
      return (static_cast<std::int64_t>(c.z()) * dims.y() + c.y()) * dims.x() + c.x();
    };
    const std::int64_t total = static_cast<std::int64_t>(dims.x()) * dims.y() * dims.z();
    cell_of_.resize(n);
    cell_start_.assign(static_cast<std::size_t>(total) + 1, 0);
    Eigen::Array3i c;
    for (std::size_t k = 0; k < n; ++k) {
      cell_of_[k] = cell_index(particles.position[k], c);
      ++cell_start_[static_cast<std::size_t>(cell_of_[k]) + 1];
    }
    std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
    sorted_.resize(n);
    {
      std::vector<std::int64_t>& fill = cell_of_;  // reuse: counting sort cursor per particle
      std::vector<std::int64_t> cursor(cell_start_.begin(), cell_start_.end() - 1);
      for (std::size_t k = 0; k < n; ++k) sorted_[static_cast<std::size_t>(cursor[static_cast<std::size_t>(fill[k])]++)] = static_cast<Index>(k);
    }
    for (std::size_t a = 0; a < n; ++a) {
      const Vec3& xa = particles.position[a];
      const double ra = particles.radius[a];
      cell_index(xa, c);
      candidates_.clear();
      for (int dz = -1; dz <= 1; ++dz) {
        const int z = c.z() + dz;
        if (z < 0 || z >= dims.z()) continue;
        for (int dy = -1; dy <= 1; ++dy) {
          const int y = c.y() + dy;
          if (y < 0 || y >= dims.y()) continue;
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = c.x() + dx;
            if (x < 0 || x >= dims.x()) continue;
            const auto id = static_cast<std::size_t>((static_cast<std::int64_t>(z) * dims.y() + y) * dims.x() + x);
            for (auto s = cell_start_[id]; s < cell_start_[id + 1]; ++s) {
              const Index b = sorted_[static_cast<std::size_t>(s)];
              if (static_cast<std::size_t>(b) <= a) continue;
              const double reach = ra + particles.radius[b] + skin_;
              if ((particles.position[b] - xa).squaredNorm() < reach * reach) candidates_.push_back(b);
            }
          }
        }
      }
      // Walls first (negative j), then particles in ascending order: the list is sorted by (i, j).
      for (std::size_t w = walls.size(); w-- > 0;) {
        Vec3 normal;
        double distance;
        if (wall_contact(walls[w], xa, ra + skin_, normal, distance)) {
          new_i_.push_back(static_cast<Index>(a));
          new_j_.push_back(-1 - static_cast<Index>(w));
        }
      }
      std::sort(candidates_.begin(), candidates_.end());
      for (Index b : candidates_) {
        new_i_.push_back(static_cast<Index>(a));
        new_j_.push_back(b);
      }
    }
  }
  // Carry the history of pairs that stay listed (both lists are sorted by (i, j)).
  new_history_.assign(new_i_.size() * stride_, 0.0);
  if (stride_ > 0) {
    std::size_t old = 0;
    for (std::size_t k = 0; k < new_i_.size(); ++k) {
      while (old < i_.size() && (i_[old] < new_i_[k] || (i_[old] == new_i_[k] && j_[old] < new_j_[k]))) ++old;
      if (old < i_.size() && i_[old] == new_i_[k] && j_[old] == new_j_[k])
        std::copy_n(history_.begin() + static_cast<std::ptrdiff_t>(old * stride_), stride_,
                    new_history_.begin() + static_cast<std::ptrdiff_t>(k * stride_));
    }
  }
  std::swap(i_, new_i_);
  std::swap(j_, new_j_);
  std::swap(history_, new_history_);
  position_at_build_ = particles.position;
  wall_displacement_at_build_.resize(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) wall_displacement_at_build_[w] = walls[w].displacement;
}

}  // namespace shard
