#pragma once
// Bond stresses (eq. 8, 9) and the von Mises criterion (eq. 10) of the seed paper.
//
// Reading of eq. 10 (the seed counts the normal stress only in tension):
//   tension  = max(E_b Gamma_x, 0)                  axial normal stress, tension only
//   bending  = E_b r_b |kappa_bend|                 outer-fibre bending stress, |(kappa_y, kappa_z)|
//   shear    = G_b |Gamma_shear|                    |(Gamma_y, Gamma_z)|
//   torsion  = G_b r_b |kappa_twist|                outer-fibre torsional shear stress
//   sigma_axial = tension + bending,  tau = shear + torsion,  sigma_vm = sqrt(sigma_axial^2 + 3 tau^2)
// The bending fibre in tension always exists, so bending counts whatever the sign of kappa.
// The dominant mode is the largest of (tension, bending, sqrt(3) shear, sqrt(3) torsion): the
// shear terms are scaled to their von Mises equivalent so the four compare in one unit.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "shard/bond_model.hpp"
#include "shard/lanes/lanes.hpp"
#include "shard/types.hpp"

namespace shard::beam {

// False only when sigma_vm < strength for certain: bounds |(a, b)| <= |a| + |b| for the bending and
// shear magnitudes, with a margin of 1e-12 against round-off, so the three square roots of
// stress_of are taken only near failure and the break decision is exactly that of stress_of.
// For any lane type T (shard/lanes/lanes.hpp).
template <class T>
inline auto may_reach(const T (&strain)[3], const T (&curvature)[3], double youngs, double shear_modulus,
                      const T& radius, const T& strength) {
  using namespace lanes;
  const T axial = max(youngs * strain[0], T(0.0)) + youngs * radius * (abs(curvature[1]) + abs(curvature[2]));
  const T tau = shear_modulus * (abs(strain[1]) + abs(strain[2])) + shear_modulus * radius * abs(curvature[0]);
  return axial * axial + 3 * tau * tau >= (1 - 1e-12) * strength * strength;
}

inline BondStress stress_of(const double (&strain)[3], const double (&curvature)[3], double youngs,
                            double shear_modulus, double radius) {
  BondStress s;
  s.tension = std::max(youngs * strain[0], 0.0);
  s.bending = youngs * radius * std::sqrt(curvature[1] * curvature[1] + curvature[2] * curvature[2]);
  s.shear = shear_modulus * std::sqrt(strain[1] * strain[1] + strain[2] * strain[2]);
  s.torsion = shear_modulus * radius * std::abs(curvature[0]);
  s.sigma_axial = s.tension + s.bending;
  s.tau = s.shear + s.torsion;
  s.sigma_vm = std::sqrt(s.sigma_axial * s.sigma_axial + 3 * s.tau * s.tau);

  const double root3 = std::sqrt(3.0);
  const double candidates[4] = {s.tension, s.bending, root3 * s.shear, root3 * s.torsion};
  const BondFailureMode modes[4] = {BondFailureMode::Tension, BondFailureMode::Bending,
                                    BondFailureMode::Shear, BondFailureMode::Torsion};
  int best = 0;
  for (int m = 1; m < 4; ++m)
    if (candidates[m] > candidates[best]) best = m;
  s.dominant = candidates[best] > 0 ? modes[best] : BondFailureMode::None;
  return s;
}

// A bond that fails this step: its stresses at failure recorded, no load on its particles.
inline void write_broken(BondBatch& batch, std::size_t k, const BondStress& s) {
  batch.broken[k] = 1;
  batch.stress[k] = s;
  batch.force[k].setZero();
  batch.torque_i[k].setZero();
  batch.torque_j[k].setZero();
  batch.energy[k] = 0;
}

}  // namespace shard::beam
