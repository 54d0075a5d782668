#pragma once
// Kernel-owned bond arrays (structure of arrays), kept sorted by first particle for locality.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shard/bond_model.hpp"
#include "shard/types.hpp"

namespace shard {

struct Bonds {
  std::vector<Index> i, j;       // particle indices in the current ordering
  std::size_t stride = 0;        // model state doubles per bond
  std::vector<double> state;     // stride * size()
  // Each bond's last force, torques and energy, kept only when `keeps_loads` (empty otherwise):
  // the step needs them only until they are added to the particles, and writing them out for
  // every bond costs ~150 bytes of memory traffic per bond per step (docs/explanation/performance.md).
  bool keeps_loads = false;
  std::vector<Vec3> force, torque_i, torque_j;
  std::vector<double> energy;
  std::vector<std::uint8_t> broken;
  std::vector<BondStress> stress;

  std::size_t size() const { return i.size(); }
  void resize(std::size_t n);
  // Keep the loads or not from now on; kept loads start at zero (the next step fills them).
  void set_keeps_loads(bool keep);
  // Drops every bond with broken[k] != 0, keeping the order of the others.
  std::size_t remove_broken();
};

// One bond failure, in the vocabulary of the field: when, where and why it cracked.
struct BondBreakEvent {
  double time = 0;
  std::int64_t step = 0;
  Index id_i = 0, id_j = 0;  // stable particle ids
  Vec3 midpoint = Vec3::Zero();
  BondStress stress;
};

}  // namespace shard
