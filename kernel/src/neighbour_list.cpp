#include "neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "huge_pages.hpp"
#include "pair_exclusion.hpp"
#include "parallel.hpp"
#include "shard/domain_exchange.hpp"

namespace shard {
namespace {

// The pair (a, b), a < b by index, oriented so that first has the smaller stable id. Not listed
// when that end is a ghost: its owner's rank computes the pair (domain_exchange.hpp).
inline void push_pair(std::vector<Index>& out_i, std::vector<Index>& out_j, const Index* id, const std::uint8_t* flags,
                      Index a, Index b) {
  const bool swap = id[b] < id[a];
  if (flags[swap ? b : a] & kGhost) return;
  out_i.push_back(swap ? b : a);
  out_j.push_back(swap ? a : b);
}

// Group key of a listed pair: its smaller particle index (the particle, for a wall pair).
inline Index key_of(Index i, Index j) { return j < 0 ? i : std::min(i, j); }

}  // namespace

NeighbourList::NeighbourList(double skin, std::size_t history_stride) : skin_(skin), stride_(history_stride) {}

bool NeighbourList::update(const Particles& particles, const std::vector<Wall>& walls) {
  if (!needs_rebuild(particles, walls)) return false;
  rebuild(particles, walls);
  return true;
}

bool NeighbourList::needs_rebuild(const Particles& particles, const std::vector<Wall>& walls) const {
  const std::size_t n = particles.size();
  double moved2 = 0;  // max is order-independent: the same answer on any thread count
#pragma omp parallel reduction(max : moved2) num_threads(team_for(n))
  {
    const Range r = range_of(n, omp_get_thread_num(), omp_get_num_threads());
    moved2 = std::max(moved2, max_displacement2(particles, r.begin, r.end));
  }
  return needs_rebuild(particles, walls, moved2);
}

double NeighbourList::max_displacement2(const Particles& particles, std::size_t begin, std::size_t end) const {
  if (position_at_build_.size() != particles.size()) return 0;  // needs_rebuild says yes anyway
  double moved2 = 0;
  const Vec3* x = particles.position.data();
  const Vec3* x0 = position_at_build_.data();
  for (std::size_t k = begin; k < end; ++k) moved2 = std::max(moved2, (x[k] - x0[k]).squaredNorm());
  return moved2;
}

bool NeighbourList::needs_rebuild(const Particles& particles, const std::vector<Wall>& walls, double moved2) const {
  const std::size_t n = particles.size();
  if (position_at_build_.size() != n || wall_displacement_at_build_.size() != walls.size() ||
      wall_angle_at_build_.size() != walls.size())
    return true;
  const double max_particle = std::sqrt(moved2);
  double max_wall = 0;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    double moved = (walls[w].displacement - wall_displacement_at_build_[w]).norm();
    // A turn by a moves a point at distance r from the axis by the chord 2 r |sin(a / 2)|.
    if (walls[w].turn_moves_surface())
      moved += 2 * std::abs(std::sin(0.5 * (walls[w].angle - wall_angle_at_build_[w]))) * wall_reach_[w];
    max_wall = std::max(max_wall, moved);
  }
  // Two particles approach each other by at most twice the largest displacement.
  return 2 * max_particle > skin_ || max_particle + max_wall > skin_;
}

void NeighbourList::remap(const std::vector<Index>& new_index) {
  const std::size_t m = i_.size();
#pragma omp parallel for schedule(static) num_threads(team_for(m))
  for (std::size_t k = 0; k < m; ++k) {
    i_[k] = new_index[static_cast<std::size_t>(i_[k])];
    if (j_[k] >= 0) j_[k] = new_index[static_cast<std::size_t>(j_[k])];
  }
  position_at_build_.clear();  // forces the next update to rebuild
}

void NeighbourList::bin_particles(const Particles& particles) {
  const std::size_t n = particles.size();
  double r_max = 0;
  Vec3 lo = particles.position[0], hi = particles.position[0];
  for (std::size_t k = 0; k < n; ++k) {
    r_max = std::max(r_max, particles.radius[k]);
    lo = lo.cwiseMin(particles.position[k]);
    hi = hi.cwiseMax(particles.position[k]);
  }
  double cell = 2 * r_max + skin_;
  // Keep the grid at most a few cells per particle, however far the particles spread.
  const Eigen::Array3d extent = (hi - lo).array() + cell;
  const auto cells_for = [&](double c) { return (extent / c).ceil().prod(); };
  while (cells_for(cell) > 8.0 * static_cast<double>(n) + 64) cell *= 1.5;
  const Eigen::Array3i dims = (extent / cell).ceil().cast<int>().max(1);
  lo_ = lo;
  cell_ = cell;
  for (int a = 0; a < 3; ++a) dims_[a] = dims[a];
  const std::size_t total = static_cast<std::size_t>(dims.x()) * static_cast<std::size_t>(dims.y()) *
                            static_cast<std::size_t>(dims.z());
  cell_of_.resize(n);
#pragma omp parallel for schedule(static) num_threads(team_for(n))
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Array3i c = ((particles.position[k] - lo).array() / cell).floor().cast<int>().min(dims - 1).max(0);
    cell_of_[k] = (static_cast<std::int64_t>(c.z()) * dims.y() + c.y()) * dims.x() + c.x();
  }
  // Counting sort by cell; within a cell particles stay in index order.
  cell_start_.assign(total + 1, 0);
  for (std::size_t k = 0; k < n; ++k) ++cell_start_[static_cast<std::size_t>(cell_of_[k]) + 1];
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
  sorted_.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    sorted_[static_cast<std::size_t>(cursor_[static_cast<std::size_t>(cell_of_[k])]++)] = static_cast<Index>(k);
}

void NeighbourList::find_pairs(const Particles& particles, const std::vector<Wall>& walls,
                               const PairExclusion* excluded) {
  const std::size_t n = particles.size();
  const int team = team_for(n);
  if (threads_.size() < static_cast<std::size_t>(team)) threads_.resize(static_cast<std::size_t>(team));
  const Index* id = particles.id.data();
  const std::uint8_t* flags = particles.flags.data();
#pragma omp parallel num_threads(team)
  {
    const int t = omp_get_thread_num();
    ThreadPairs& out = threads_[static_cast<std::size_t>(t)];
    out.i.clear();
    out.j.clear();
    const Range r = range_of(n, t, omp_get_num_threads());
    for (std::size_t a = r.begin; a < r.end; ++a) {
      const Vec3& xa = particles.position[a];
      const double ra = particles.radius[a];
      const auto cell = cell_of_[a];
      const int cx = static_cast<int>(cell % dims_[0]);
      const int cy = static_cast<int>((cell / dims_[0]) % dims_[1]);
      const int cz = static_cast<int>(cell / (static_cast<std::int64_t>(dims_[0]) * dims_[1]));
      out.candidates.clear();
      for (int z = std::max(cz - 1, 0); z <= std::min(cz + 1, dims_[2] - 1); ++z) {
        for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, dims_[1] - 1); ++y) {
          const auto row = (static_cast<std::int64_t>(z) * dims_[1] + y) * dims_[0];
          // The three cells of a row are contiguous in the sorted array.
          const auto from = cell_start_[static_cast<std::size_t>(row + std::max(cx - 1, 0))];
          const auto to = cell_start_[static_cast<std::size_t>(row + std::min(cx + 1, dims_[0] - 1)) + 1];
          for (auto s = from; s < to; ++s) {
            const Index b = sorted_[static_cast<std::size_t>(s)];
            if (static_cast<std::size_t>(b) <= a) continue;
            const double reach = ra + particles.radius[b] + skin_;
            if ((particles.position[b] - xa).squaredNorm() < reach * reach &&
                !(excluded && excluded->contains(static_cast<Index>(a), b)))
              out.candidates.push_back(b);
          }
        }
      }
      // Walls first (negative j), then particles in ascending order.
      for (std::size_t w = walls.size(); w-- > 0;) {
        Vec3 normal;
        double distance;
        if (!(particles.flags[a] & kGhost) && wall_contact(walls[w], xa, ra + skin_, normal, distance)) {
          out.i.push_back(static_cast<Index>(a));
          out.j.push_back(-1 - static_cast<Index>(w));
        }
      }
      std::sort(out.candidates.begin(), out.candidates.end());
      for (Index b : out.candidates) push_pair(out.i, out.j, id, flags, static_cast<Index>(a), b);
    }
  }
  // Concatenate in thread order: the same list as one thread would have made.
  std::size_t total = 0;
  for (int t = 0; t < team; ++t) total += threads_[static_cast<std::size_t>(t)].i.size();
  resize_on_huge_pages(new_i_, total);
  resize_on_huge_pages(new_j_, total);
  std::size_t offset = 0;
  for (int t = 0; t < team; ++t) {
    const ThreadPairs& p = threads_[static_cast<std::size_t>(t)];
    std::copy(p.i.begin(), p.i.end(), new_i_.begin() + static_cast<std::ptrdiff_t>(offset));
    std::copy(p.j.begin(), p.j.end(), new_j_.begin() + static_cast<std::ptrdiff_t>(offset));
    offset += p.i.size();
  }
}

void NeighbourList::carry_history(std::size_t particle_count) {
  assign_on_huge_pages(new_history_, new_i_.size() * stride_, 0.0);
  new_touching_.assign(new_i_.size(), 0);
  if (i_.empty()) return;  // without history the touching flags still follow (wall impacts count them)
  // Group the old pairs by their smaller index (counting sort), then look each new pair up in
  // its group of at most a dozen.
  // A restored list may name particles that no longer exist: those pairs carry nothing.
  const std::size_t old = i_.size();
  const auto group = [&](std::size_t k) { return static_cast<std::size_t>(key_of(i_[k], j_[k])); };
  old_start_.assign(particle_count + 1, 0);
  for (std::size_t k = 0; k < old; ++k)
    if (group(k) < particle_count) ++old_start_[group(k) + 1];
  std::partial_sum(old_start_.begin(), old_start_.end(), old_start_.begin());
  cursor_.assign(old_start_.begin(), old_start_.end() - 1);
  old_slot_.resize(static_cast<std::size_t>(old_start_.back()));
  for (std::size_t k = 0; k < old; ++k)
    if (group(k) < particle_count)
      old_slot_[static_cast<std::size_t>(cursor_[group(k)]++)] = static_cast<std::int64_t>(k);
  const std::size_t m = new_i_.size();
#pragma omp parallel for schedule(static) num_threads(team_for(m))
  for (std::size_t k = 0; k < m; ++k) {
    const Index a = new_i_[k], b = new_j_[k];
    const auto key = static_cast<std::size_t>(key_of(a, b));
    for (auto s = old_start_[key]; s < old_start_[key + 1]; ++s) {
      const auto o = static_cast<std::size_t>(old_slot_[static_cast<std::size_t>(s)]);
      if (i_[o] == a && j_[o] == b) {
        std::copy_n(history_.begin() + static_cast<std::ptrdiff_t>(o * stride_), stride_,
                    new_history_.begin() + static_cast<std::ptrdiff_t>(k * stride_));
        new_touching_[k] = touching_[o];
        break;
      }
    }
  }
}

void NeighbourList::rebuild(const Particles& particles, const std::vector<Wall>& walls,
                            const PairExclusion* excluded) {
  ++rebuilds_;
  const std::size_t n = particles.size();
  new_i_.clear();
  new_j_.clear();
  if (n > 0) {
    bin_particles(particles);
    find_pairs(particles, walls, excluded);
  }
  carry_history(n);
  std::swap(i_, new_i_);
  std::swap(j_, new_j_);
  std::swap(history_, new_history_);
  std::swap(touching_, new_touching_);
  position_at_build_ = particles.position;
  wall_displacement_at_build_.resize(walls.size());
  wall_angle_at_build_.resize(walls.size());
  wall_reach_.assign(walls.size(), 0.0);
  for (std::size_t w = 0; w < walls.size(); ++w) {
    wall_displacement_at_build_[w] = walls[w].displacement;
    wall_angle_at_build_[w] = walls[w].angle;
    if (walls[w].turn_moves_surface()) wall_reach_[w] = spin_reach(particles, walls[w].centre());
  }
}

// How far from a spinning wall's axis point the surface can touch a particle before the next
// rebuild: the farthest particle now, its radius, and the skin twice (half of it for the particle's
// own travel, the rest for the wall's translation, each bounded by the rebuild test).
double NeighbourList::spin_reach(const Particles& particles, const Vec3& centre) const {
  double far = 0, r_max = 0;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    far = std::max(far, (particles.position[k] - centre).norm());
    r_max = std::max(r_max, particles.radius[k]);
  }
  return far + r_max + 2 * skin_;
}

}  // namespace shard
