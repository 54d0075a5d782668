#pragma once
// The load curve of a loading test, one type from the run driver (recorded live) through
// `shard bending` (read back from run.h5) to the measurement workflow (measured or simulated
// specimens), and the one rule by which the loading walls' force and displacement become it.
//
// Sign convention, SI units: time s; displacement of the loading pins m, positive along the
// loading direction (into the specimen); force on the pins N, positive when the specimen pushes
// back against their motion.
#include <cstddef>
#include <string>
#include <vector>

#include "shard/types.hpp"

namespace shard::analysis {

struct LoadCurve {
  std::string id;  // a specimen's name; empty for a run's own curve
  std::vector<double> time, displacement, force;  // time may be empty for a measured curve
  // Standard uncertainty of each displacement and force value, the length of `force`; empty when
  // the curve comes without them (a run's curve, a curve read by `shard bending`).
  std::vector<double> u_displacement, u_force;
  std::size_t size() const { return force.size(); }
};

// The testing machine's load cell and displacement gauge over the loading walls ([stop]
// load_walls): the force the particles push them back with, summed over the walls, and the walls'
// mean displacement, both along the loading direction (a unit vector). The same arithmetic live
// in a run (shard/driver/load_sensor.hpp) and on a run file's wall series (shard bending), so the
// two agree to the last bit.
class PinReading {
 public:
  explicit PinReading(const Vec3& direction) : direction_(direction) {}
  void add_wall(const Vec3& wall_force, const Vec3& wall_displacement) {
    force_ -= wall_force.dot(direction_);
    displacement_sum_ += wall_displacement.dot(direction_);
    ++walls_;
  }
  double force() const { return force_; }  // N
  // m; 0 without loading walls.
  double displacement() const { return walls_ == 0 ? 0.0 : displacement_sum_ / static_cast<double>(walls_); }

 private:
  Vec3 direction_;
  double force_ = 0, displacement_sum_ = 0;
  std::size_t walls_ = 0;
};

}  // namespace shard::analysis
