#pragma once
// Verlet neighbour list built from a cell list. Pairs (particle-particle and particle-wall) within
// the interaction range plus a skin are kept until some particle or wall has moved more than half
// the skin. Contact history lives here, per listed pair, and is carried across rebuilds and
// across reorderings of the particles.
//
// Pair orientation: `first` is the particle with the smaller stable id (Particles::id), so a pair
// keeps its orientation, and its history its sign, when the kernel renumbers particles. Pairs are
// listed by their smaller index, walls (second < 0) before particles, then by the larger index.
#include <cstdint>
#include <vector>

#include "shard/particles.hpp"
#include "shard/wall.hpp"

namespace shard {

struct NeighbourState;
class PairExclusion;

class NeighbourList {
 public:
  NeighbourList(double skin, std::size_t history_stride);

  // Rebuilds when needed; returns true if it did.
  bool update(const Particles& particles, const std::vector<Wall>& walls);
  bool needs_rebuild(const Particles& particles, const std::vector<Wall>& walls) const;
  // The same with the particles' part known: `moved2` the largest squared displacement since the
  // build over all particles, gathered by the caller from max_displacement2 over its ranges (the
  // drift does, while the positions are in cache and without a parallel region of its own).
  bool needs_rebuild(const Particles& particles, const std::vector<Wall>& walls, double moved2) const;
  double max_displacement2(const Particles& particles, std::size_t begin, std::size_t end) const;
  // `excluded`: particle pairs not to list (pair_exclusion.hpp); null lists every pair in range.
  void rebuild(const Particles& particles, const std::vector<Wall>& walls, const PairExclusion* excluded = nullptr);
  // The next update rebuilds (a pair left out may have to be listed now).
  void invalidate() { position_at_build_.clear(); }
  // The particles were renumbered: old index k is now new_index[k]. Pairs and history follow;
  // call rebuild() next (the build positions are stale).
  void remap(const std::vector<Index>& new_index);

  std::size_t size() const { return i_.size(); }
  const std::vector<Index>& first() const { return i_; }
  const std::vector<Index>& second() const { return j_; }  // j < 0: wall -1 - j
  std::vector<double>& history() { return history_; }
  // Per pair: 1 if it touched at the last force pass, so its history may be non-zero; 0 means
  // the history is zero. The contact pass keeps it; it follows the pairs like the history, and a
  // restored list derives it from the history. The contact pass reads this byte instead of the
  // history of the many pairs that are not touching.
  std::vector<std::uint8_t>& touching() { return touching_; }
  std::size_t history_stride() const { return stride_; }
  std::int64_t rebuilds() const { return rebuilds_; }
  double skin() const { return skin_; }
  NeighbourState state() const;  // neighbour_list_restore.cpp: checkpoints
  void restore(const NeighbourState& state);
  void restore(NeighbourState&& state);
  // The state moved out (a decomposed run's re-partition edits it in place); restore() before
  // the list is used again.
  NeighbourState take_state();

 private:
  void bin_particles(const Particles& particles);
  void find_pairs(const Particles& particles, const std::vector<Wall>& walls, const PairExclusion* excluded);
  void carry_history(std::size_t particle_count);
  double spin_reach(const Particles& particles, const Vec3& centre) const;

  // Pairs found by one thread for its range of particles; reused from rebuild to rebuild.
  struct ThreadPairs {
    std::vector<Index> i, j, candidates;
  };

  double skin_;
  std::size_t stride_;
  std::vector<Index> i_, j_;
  std::vector<double> history_;
  std::vector<std::uint8_t> touching_;
  // Double buffers reused at every rebuild so rebuilding does not allocate once warmed up.
  std::vector<Index> new_i_, new_j_;
  std::vector<double> new_history_;
  std::vector<std::uint8_t> new_touching_;
  std::vector<Vec3> position_at_build_;
  std::vector<Vec3> wall_displacement_at_build_;
  std::vector<double> wall_angle_at_build_;  // rad, of spinning walls
  std::vector<double> wall_reach_;           // m: the largest distance from a spinning wall's axis point that matters
  // Cell list: particles sorted by cell (counting sort), grid geometry of the last build.
  std::vector<std::int64_t> cell_of_;
  std::vector<Index> sorted_;
  std::vector<std::int64_t> cell_start_, cursor_;
  Vec3 lo_ = Vec3::Zero();
  double cell_ = 1;
  std::int32_t dims_[3] = {1, 1, 1};
  std::vector<ThreadPairs> threads_;
  // Old pairs grouped by their smaller index, to find a new pair's history in O(1).
  std::vector<std::int64_t> old_start_;
  std::vector<std::int64_t> old_slot_;
  std::int64_t rebuilds_ = 0;
};

}  // namespace shard
