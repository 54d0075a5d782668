#pragma once
// Verlet neighbour list built from a cell list. Pairs (particle-particle and particle-wall) within
// the interaction range plus a skin are kept until some particle or wall has moved more than half
// the skin. Contact history lives here, per listed pair, and is carried across rebuilds.
#include <cstdint>
#include <vector>

#include "shard/particles.hpp"
#include "shard/wall.hpp"

namespace shard {

class NeighbourList {
 public:
  NeighbourList(double skin, std::size_t history_stride);

  // Rebuilds when needed; returns true if it did.
  bool update(const Particles& particles, const std::vector<Wall>& walls);
  std::size_t size() const { return i_.size(); }
  const std::vector<Index>& first() const { return i_; }
  const std::vector<Index>& second() const { return j_; }  // j < 0: wall -1 - j
  std::vector<double>& history() { return history_; }
  std::size_t history_stride() const { return stride_; }
  std::int64_t rebuilds() const { return rebuilds_; }
  double skin() const { return skin_; }

 private:
  bool needs_rebuild(const Particles& particles, const std::vector<Wall>& walls) const;
  void rebuild(const Particles& particles, const std::vector<Wall>& walls);

  double skin_;
  std::size_t stride_;
  std::vector<Index> i_, j_;
  std::vector<double> history_;
  // Double buffers reused at every rebuild so rebuilding does not allocate once warmed up.
  std::vector<Index> new_i_, new_j_;
  std::vector<double> new_history_;
  std::vector<Vec3> position_at_build_;
  std::vector<Vec3> wall_displacement_at_build_;
  std::vector<std::int64_t> cell_of_;
  std::vector<Index> sorted_;
  std::vector<std::int64_t> cell_start_;
  std::vector<Index> candidates_;
  std::int64_t rebuilds_ = 0;
};

}  // namespace shard
