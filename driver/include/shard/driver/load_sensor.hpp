#pragma once
// The testing machine's load cell and displacement gauge: the [stop] load walls' force against
// their motion, and their mean displacement, along the loading direction.
#include <cstddef>
#include <vector>

#include "shard/scene.hpp"
#include "shard/simulation.hpp"

namespace shard::driver {

class LoadSensor {
 public:
  LoadSensor(const Scene& scene, const Simulation& sim);
  bool empty() const { return walls_.empty(); }
  // N: the particles push back against the motion of the loading walls.
  double load(const Simulation& sim) const;
  // m: the walls' mean displacement (0 without load walls).
  double displacement(const Simulation& sim) const;

 private:
  std::vector<std::size_t> walls_;
  Vec3 direction_;
};

}  // namespace shard::driver
