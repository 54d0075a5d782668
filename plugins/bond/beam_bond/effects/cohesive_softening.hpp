#pragma once
// Linear (bilinear cohesive) softening of a bond after its strength is reached.
//
// Equivalent strain eps = sigma_vm / E_b (for pure tension: the axial strain). Up to
// eps0 = sigma_c / E_b the bond is elastic; beyond it the stress it can carry falls linearly,
//   sigma(eps) = sigma_c (eps_f - eps) / (eps_f - eps0),   eps_f = eps0 (1 + s),  s = softening_ratio,
// reaching zero at eps_f where the bond breaks. This is written as an isotropic damage D that
// scales the bond's elastic (and viscous) force and torque by (1 - D):
//   D(eps) = 1 - sigma(eps) / (E_b eps),
// and D never decreases, so unloading runs back to the origin along the secant (1 - D) E_b.
// Work to break a bar of length l0 and area A in tension: W = sigma_c A l0 eps_f / 2, i.e. the
// elastic energy at the peak times (1 + s): s is the ratio of the fracture energy to the peak
// elastic energy. s = 0 is brittle: the bond breaks the moment sigma_vm reaches sigma_c.
#include <algorithm>

namespace shard::beam {

// Damage implied by a trial (undamaged) von Mises stress sigma_vm >= sigma_c; >= 1 means broken.
inline double softening_damage(double sigma_vm, double sigma_c, double softening_ratio) {
  // With E (eps_f - eps0) = s sigma_c, sigma(eps) = E (eps_f - eps) / s; E cancels in D.
  const double remaining = sigma_c * (1 + softening_ratio) - sigma_vm;  // E (eps_f - eps)
  if (remaining <= 0) return 1;
  return std::max(0.0, 1 - remaining / (softening_ratio * sigma_vm));
}

}  // namespace shard::beam
