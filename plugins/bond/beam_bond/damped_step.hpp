#pragma once
// The stable step of the explicit integrator when the bonds carry dashpots (eq. 4's force damping,
// c in N s/m). Written as c = tau K for a bond of axial stiffness K, the dashpot damps the
// network's mode of frequency omega with the ratio z = tau omega / 2. The elastic step resolves
// omega_max = 2 / dt_elastic, where z = tau / dt_elastic, and central differences with the lagged
// velocity stay stable for omega dt <= 2 (sqrt(1 + z^2) - z) = 2 / (sqrt(1 + z^2) + z). Taking tau
// from the softest bond (c / K_min) bounds z for every bond.
#include <cmath>

namespace shard::beam {

inline double damped_step(double elastic_step, double tau) {
  if (!(tau > 0)) return elastic_step;
  const double z = tau / elastic_step;
  return elastic_step / (std::sqrt(1 + z * z) + z);
}

}  // namespace shard::beam
