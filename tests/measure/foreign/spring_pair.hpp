#pragma once
// The foreign spring bond driven by hand on one bonded pair along x (the tests of the law and of
// its effects), with the kernel-free batch of tests/bond/bond_pair.hpp.
#include <cmath>

#include "../../bond/bond_pair.hpp"
#include "foreign_spring_bond.hpp"

namespace shard::foreign_test {

// The defaults of the law without damping, so a static pair's loads are the springs' alone.
inline foreign::SpringBondParams undamped() {
  foreign::SpringBondParams p;
  p.damping_ratio = 0;
  return p;
}

struct SpringPair {
  static constexpr double radius = 0.85e-3;  // m, the foreign beam's mean sphere
  static constexpr double rest = 2 * radius;
  test::HandBonds scene;

  explicit SpringPair(const BondModel& model) {
    scene.add_sphere(Vec3::Zero(), radius);
    scene.add_sphere(Vec3(rest, 0, 0), radius);
    scene.add_bond(0, 1);
    scene.initialize(model);
  }
  // Second sphere at (rest + dx, dy, 0); orientations of the two spheres.
  void place(double dx, double dy = 0, const Quat& q_first = Quat::Identity(), const Quat& q_second = Quat::Identity()) {
    scene.position[1] = Vec3(rest + dx, dy, 0);
    scene.orientation[0] = q_first;
    scene.orientation[1] = q_second;
  }
  void compute(const BondModel& model) { scene.compute(model); }
  const Vec3& force_on_first() const { return scene.force[0]; }
  bool broken() const { return scene.broken[0] != 0; }
};

}  // namespace shard::foreign_test
