#pragma once
// Cohesion of touching particles as a constant pull per contact area (the "linear cohesion"
// simplification of JKR): while two spheres overlap by delta, a force
//   F_c = sigma_c A,   A = pi a^2 = pi R* delta   (Hertz contact radius a = sqrt(R* delta))
// pulls them together; it vanishes when they separate (delta = 0), so there is no neck and no
// hysteresis as in full JKR. Its potential is U_c = -sigma_c pi R* delta^2 / 2.
// With the Hertz repulsion 4/3 E* sqrt(R*) delta^1.5 the net normal force is attractive below
//   delta_eq = (3 pi sigma_c sqrt(R*) / (4 E*))^2
// and most attractive at delta* = (pi sigma_c)^2 R* / (4 E*^2), where the pull needed to separate
// the pair quasi-statically is the pull-off force
//   F_po = (pi sigma_c)^3 R*^2 / (12 E*^2).
#include <numbers>

namespace shard::cohesion {

inline double contact_area(double R, double delta) { return std::numbers::pi * R * delta; }

inline double cohesive_force(double sigma_c, double R, double delta) { return sigma_c * contact_area(R, delta); }

inline double cohesive_energy(double sigma_c, double R, double delta) {
  return -0.5 * sigma_c * std::numbers::pi * R * delta * delta;
}

inline double pull_off_force(double sigma_c, double R, double E_star) {
  const double p = std::numbers::pi * sigma_c;
  return p * p * p * R * R / (12 * E_star * E_star);
}

}  // namespace shard::cohesion
