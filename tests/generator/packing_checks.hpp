#pragma once
// Figures of a generated body that the generator tests assert on.
#include <array>
#include <cmath>
#include <numbers>

#include "shard/generator.hpp"
#include "shard/geometry/stl.hpp"

namespace shard::test {

// Share of each face of an axis-aligned box covered by the discs of the spheres that touch it
// (their outermost point within `tolerance` of the face).
inline std::array<double, 6> touching_area_fraction(const GeneratedBody& body, const geometry::Box& box, double tolerance) {
  std::array<double, 6> covered{};
  const Vec3 extent = box.upper - box.lower;
  for (std::size_t i = 0; i < body.position.size(); ++i) {
    const Vec3& c = body.position[i];
    const double r = body.radius[i];
    for (int axis = 0; axis < 3; ++axis) {
      if (std::abs(c[axis] - r - box.lower[axis]) <= tolerance) covered[2 * axis] += std::numbers::pi * r * r;
      if (std::abs(box.upper[axis] - c[axis] - r) <= tolerance) covered[2 * axis + 1] += std::numbers::pi * r * r;
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    const double area = extent[(axis + 1) % 3] * extent[(axis + 2) % 3];
    covered[2 * axis] /= area;
    covered[2 * axis + 1] /= area;
  }
  return covered;
}

}  // namespace shard::test
