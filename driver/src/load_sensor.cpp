#include "shard/driver/load_sensor.hpp"

namespace shard::driver {

LoadSensor::LoadSensor(const Scene& scene, const Simulation& sim) : direction_(scene.stop.load_direction) {
  for (const auto& name : scene.stop.load_walls)
    for (std::size_t w = 0; w < sim.walls().size(); ++w)
      if (sim.walls()[w].name == name) walls_.push_back(w);
}

analysis::PinReading LoadSensor::read(const Simulation& sim) const {
  analysis::PinReading reading(direction_);
  for (auto w : walls_) reading.add_wall(sim.walls()[w].force, sim.walls()[w].displacement);
  return reading;
}

}  // namespace shard::driver
