#pragma once
// beam_bond with its effect policies driven directly (the model library), on one bonded pair along x.
#include <cmath>
#include <numbers>

#include "beam_bond_model.hpp"
#include "bond_batch.hpp"

namespace shard::effects_test {

// Seed Table I bond: E_b = 12.8 MPa, sigma_crit = 0.24 MPa, r = 0.35 mm, no damping.
inline beam::BeamBondParams table_one_params() {
  beam::BeamBondParams p;
  p.damping = 0;
  p.rotational_damping = 0;
  return p;
}

struct Pair {
  static constexpr double radius = 0.35e-3;
  static constexpr double l0 = 2 * radius;
  static constexpr double area = std::numbers::pi * radius * radius;  // A_b with lambda = 1
  BondScene scene;

  explicit Pair(const BondModel& model) {
    scene.add_sphere(Vec3::Zero(), radius);
    scene.add_sphere(Vec3(l0, 0, 0), radius);
    scene.add_bond(0, 1);
    scene.initialize(model);
  }
  // Places the second sphere at axial strain eps (transverse offset y_offset), moving at v.
  void set(double eps, const Vec3& v = Vec3::Zero(), double y_offset = 0) {
    scene.position[1] = Vec3(l0 * (1 + eps), y_offset, 0);
    scene.velocity[1] = v;
  }
  // Axial force on the first sphere, > 0 in tension (the bond pulls it towards the second).
  double axial_force(const BondModel& model) {
    scene.compute(model);
    return scene.force[0].x();
  }
  bool broken() const { return scene.broken[0] != 0; }
  double damage() const { return scene.state[beam::kDamageSlot]; }
};

}  // namespace shard::effects_test
