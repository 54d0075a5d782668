#pragma once
// Eq. 12's stable step for a batch of beam bonds, t_bond = 0.17 sqrt(m / K): the lightest bonded
// particle against the stiffest bond, K = E A / l0, then shortened for eq. 4's dashpot c with
// tau = c / K_min of the softest bond (damped_step.hpp). Every beam-bond plugin states the moduli
// its axial spring can reach; the loop over the bonds is this one.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "beam_geometry.hpp"
#include "damped_step.hpp"
#include "shard/bond_model.hpp"

namespace shard::beam {

struct AxialModuli {
  double stiffest = 0;  // Pa, the largest modulus the axial spring can reach (sets K_max)
  double softest = 0;   // Pa, the smallest (sets K_min for the dashpot)
};

// `stride` doubles of state per bond, l0 the first; `damping` is eq. 4's c, N s/m.
inline double eq12_step(const BondBatch& batch, std::size_t stride, double radius_ratio, AxialModuli moduli,
                        double damping) {
  const ParticleView& p = batch.particles;
  double lightest = std::numeric_limits<double>::infinity();
  double stiffest = 0, softest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Index i = batch.i[k], j = batch.j[k];
    const double l0 = batch.state[k * stride];
    const Section sec = section_of(radius_ratio, p.radius[i], p.radius[j]);
    stiffest = std::max(stiffest, moduli.stiffest * sec.area / l0);
    softest = std::min(softest, moduli.softest * sec.area / l0);
    lightest = std::min({lightest, p.mass[i], p.mass[j]});
  }
  if (!(stiffest > 0)) return std::numeric_limits<double>::infinity();
  return damped_step(0.17 * std::sqrt(lightest / stiffest), damping / softest);
}

}  // namespace shard::beam
