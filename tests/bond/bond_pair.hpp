#pragma once
// A hand-built set of particles and bonds for driving a BondModel directly, without the kernel.
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "shard/bond_model.hpp"
#include "shard/types.hpp"

namespace shard::test {

struct HandBonds {
  std::vector<Vec3> position, velocity, omega;
  std::vector<Quat> orientation;
  std::vector<double> radius, mass, inertia;
  std::vector<std::int32_t> material;
  std::vector<Index> id;
  std::vector<std::uint8_t> flags;  // ParticleFlag bits per sphere; empty: none set

  std::vector<Index> i, j;
  std::vector<double> state;
  std::vector<Vec3> force, torque_i, torque_j;
  std::vector<double> energy;
  std::vector<std::uint8_t> broken;
  std::vector<BondStress> stress;

  Index add_sphere(const Vec3& x, double r, double density = 3720) {
    const double m = density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
    position.push_back(x);
    velocity.push_back(Vec3::Zero());
    omega.push_back(Vec3::Zero());
    orientation.push_back(Quat::Identity());
    radius.push_back(r);
    mass.push_back(m);
    inertia.push_back(0.4 * m * r * r);
    material.push_back(0);
    id.push_back(static_cast<Index>(id.size()));
    return id.back();
  }

  void add_bond(Index a, Index b) {
    i.push_back(a);
    j.push_back(b);
  }

  double dt = 0;  // s, handed to the model in every batch (rate-dependent models read it)

  // A batch over all bonds, outputs prepared as the kernel does: zeroed, or, for a model that
  // declares it writes every output, filled with NaN so that an output it forgot shows in any
  // comparison. The model state is kept.
  BondBatch batch(const BondModel& model) {
    const std::size_t n = i.size();
    state.resize(n * model.state_size());
    const double unset = model.writes_every_output() ? std::numeric_limits<double>::quiet_NaN() : 0.0;
    force.assign(n, Vec3::Constant(unset));
    torque_i.assign(n, Vec3::Constant(unset));
    torque_j.assign(n, Vec3::Constant(unset));
    energy.assign(n, unset);
    broken.assign(n, 0);
    stress.assign(n, BondStress{});
    BondBatch b;
    b.count = n;
    b.dt = dt;
    b.i = i.data();
    b.j = j.data();
    b.particles.count = position.size();
    b.particles.position = position.data();
    b.particles.velocity = velocity.data();
    b.particles.orientation = orientation.data();
    b.particles.omega = omega.data();
    b.particles.radius = radius.data();
    b.particles.mass = mass.data();
    b.particles.inertia = inertia.data();
    b.particles.material = material.data();
    b.particles.id = id.data();
    b.particles.flags = flags.empty() ? nullptr : flags.data();
    b.state = state.data();
    b.force = force.data();
    b.torque_i = torque_i.data();
    b.torque_j = torque_j.data();
    b.energy = energy.data();
    b.broken = broken.data();
    b.stress = stress.data();
    return b;
  }

  void initialize(const BondModel& model) {
    BondBatch b = batch(model);
    model.initialize(b);
  }

  // Evaluates the bonds in the current configuration, keeping the recorded reference state.
  void compute(const BondModel& model) {
    BondBatch b = batch(model);
    model.compute(b);
  }
};

}  // namespace shard::test
