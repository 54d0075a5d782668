#pragma once
// A force-displacement curve of one four-point bending test, SI units: time s, displacement of
// the loading pins m (positive downwards into the specimen), force on the pins N (positive when
// the specimen pushes back), with the standard uncertainty of each displacement and force value.
#include <string>
#include <vector>

namespace shard::measure {

struct Curve {
  std::string id;
  std::vector<double> time, displacement, force;
  std::vector<double> u_displacement, u_force;  // standard uncertainties, same length
  std::size_t size() const { return force.size(); }
};

}  // namespace shard::measure
