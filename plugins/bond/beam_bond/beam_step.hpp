#pragma once
// One bond of a batch through beam_law at width 1 (T = double): the scalar reference, what runs
// the lanes the block step leaves, and what a plugin built on the beam calls with its own extra
// break criterion (docs/tutorials/crushing_bond). Writes the bond's outputs in the batch's
// orientation, its state (damage, the Maxwell arm) and, when it fails, its stresses.
#include <cstddef>

#include "beam_geometry.hpp"
#include "beam_law.hpp"
#include "beam_stress.hpp"
#include "shard/bond_model.hpp"

namespace shard::beam {

template <bool breakage, bool viscous, bool effects, bool arm, class Extra>
inline void step_bond(BondBatch& batch, std::size_t k, std::size_t stride, const LawConstants& c, const Extra& extra) {
  const ParticleView& p = batch.particles;
  const Ends e = ends_of(p, batch.i[k], batch.j[k]);
  double* state = batch.state + k * stride;
  BondLanes<double> bond;
  const Quat& q1 = p.orientation[e.first];
  const Quat& q2 = p.orientation[e.second];
  bond.q1 = {q1.w(), q1.x(), q1.y(), q1.z()};
  bond.q2 = {q2.w(), q2.x(), q2.y(), q2.z()};
  for (int d = 0; d < 3; ++d) {
    bond.x1[d] = p.position[e.first][d];
    bond.x2[d] = p.position[e.second][d];
    bond.w1[d] = p.omega[e.first][d];
    bond.w2[d] = p.omega[e.second][d];
    if constexpr (viscous) {
      bond.v1[d] = p.velocity[e.first][d];
      bond.v2[d] = p.velocity[e.second][d];
    }
  }
  bond.r1 = p.radius[e.first];
  bond.r2 = p.radius[e.second];
  bond.i1 = p.inertia[e.first];
  bond.i2 = p.inertia[e.second];
  for (std::size_t s = 0; s < stride; ++s) bond.state[s] = state[s];

  const BondLoads<double> r = beam_law<double, true, breakage, viscous, effects, arm>(bond, c, extra);
  if constexpr (arm)  // the arm advances whether or not the bond fails this step
    for (std::size_t s = 0; s < 12; ++s) state[kPreviousStrainSlot + s] = r.next_arm[s];
  if (r.broken) {
    write_broken(batch, k, r.stress);
    return;
  }
  if constexpr (effects) state[kDamageSlot] = r.damage;
  const Vec3 force(r.force[0], r.force[1], r.force[2]);
  const Vec3 first(r.torque_first[0], r.torque_first[1], r.torque_first[2]);
  const Vec3 second(r.torque_second[0], r.torque_second[1], r.torque_second[2]);
  batch.force[k] = e.swapped ? Vec3(-force) : force;
  batch.torque_i[k] = e.swapped ? second : first;
  batch.torque_j[k] = e.swapped ? first : second;
  batch.energy[k] = r.energy;
}

// The same with the law's switches read from the constants.
template <class Extra>
inline void step_bond(BondBatch& batch, std::size_t k, std::size_t stride, const LawConstants& c, const Extra& extra) {
  auto with = [&]<bool breakage, bool viscous>() {
    if (!c.effects) step_bond<breakage, viscous, false, false>(batch, k, stride, c, extra);
    else if (c.arm) step_bond<breakage, viscous, true, true>(batch, k, stride, c, extra);
    else step_bond<breakage, viscous, true, false>(batch, k, stride, c, extra);
  };
  // A bond of an unbreakable zone takes the law without its breakage check (an intact bond).
  if (c.breakage && !bond_unbreakable(batch.particles, batch.i[k], batch.j[k])) {
    if (c.viscous_force) with.template operator()<true, true>();
    else with.template operator()<true, false>();
  } else {
    if (c.viscous_force) with.template operator()<false, true>();
    else with.template operator()<false, false>();
  }
}

}  // namespace shard::beam
