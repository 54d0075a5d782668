#pragma once
// The testing machine's load cell and displacement gauge on a running simulation: the [stop] load
// walls read by the one load rule (shard/analysis/load_curve.hpp, PinReading).
#include <cstddef>
#include <vector>

#include "shard/analysis/load_curve.hpp"
#include "shard/scene.hpp"
#include "shard/simulation.hpp"

namespace shard::driver {

class LoadSensor {
 public:
  LoadSensor(const Scene& scene, const Simulation& sim);
  bool empty() const { return walls_.empty(); }
  analysis::PinReading read(const Simulation& sim) const;
  // N: the particles push back against the motion of the loading walls.
  double load(const Simulation& sim) const { return read(sim).force(); }
  // m: the walls' mean displacement (0 without load walls).
  double displacement(const Simulation& sim) const { return read(sim).displacement(); }

 private:
  std::vector<std::size_t> walls_;
  Vec3 direction_;
};

}  // namespace shard::driver
