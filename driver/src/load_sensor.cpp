#include "shard/driver/load_sensor.hpp"

namespace shard::driver {

LoadSensor::LoadSensor(const Scene& scene, const Simulation& sim) : direction_(scene.stop.load_direction) {
  for (const auto& name : scene.stop.load_walls)
    for (std::size_t w = 0; w < sim.walls().size(); ++w)
      if (sim.walls()[w].name == name) walls_.push_back(w);
}

double LoadSensor::load(const Simulation& sim) const {
  double f = 0;
  for (auto w : walls_) f -= sim.walls()[w].force.dot(direction_);
  return f;
}

double LoadSensor::displacement(const Simulation& sim) const {
  if (walls_.empty()) return 0;
  double d = 0;
  for (auto w : walls_) d += sim.walls()[w].displacement.dot(direction_);
  return d / static_cast<double>(walls_.size());
}

}  // namespace shard::driver
