#pragma once
// The four-point bending set-up read from its cylinders and its spheres, one rule for the bending
// report of a run (bending_run.hpp) and the specimen a measurement command simulates
// (apps/src/measure_runner.hpp): the beam axis runs from the first loading pin to the second with
// its component along the load direction removed; distances between cylinders are measured
// along that axis; the specimen's size is the spheres' extent along it, across it and along the
// load.
#include <span>

#include "shard/types.hpp"

namespace shard::bending {

struct BeamFrame {
  Vec3 centre = Vec3::Zero();  // midway between the loading pins
  Vec3 axis = Vec3::UnitX(), across = Vec3::UnitY(), down = -Vec3::UnitZ();
};

// Throws std::invalid_argument when the pins coincide across the load direction. The axis sign is
// fixed (positive sum of components), so every run of one scene reports the same signed crack.
BeamFrame beam_frame(const Vec3& pin_a, const Vec3& pin_b, const Vec3& down);

// |(b - a) . axis|: the span between two supports, the distance between two pins.
double distance_along(const BeamFrame& frame, const Vec3& a, const Vec3& b);

struct SphereExtent {
  double length = 0, width = 0, height = 0;  // m, along the axis, across it, along the load
  double mid_height = 0;  // m, the middle of the height band, from the centre along the load
};
SphereExtent sphere_extent(const BeamFrame& frame, std::span<const Vec3> positions, std::span<const double> radii);

}  // namespace shard::bending
