#pragma once
// Rate dependence as a standard linear solid (Zener), in the Maxwell form: each strain and
// curvature component of the bond has the elastic beam (modulus E_b) in parallel with a Maxwell
// arm, a spring beta E_b in series with a dashpot of viscosity eta = E_b tau_v. The arm carries the
// stress E_b h, with h its "arm strain", which obeys
//   dh/dt = beta dGamma/dt - h / tau_r,      tau_r = tau_v / beta   (the arm's relaxation time).
// Loaded slowly against tau_r the arm is a dashpot: h -> tau_v dGamma/dt, the Kelvin-Voigt stress
// E_b (Gamma + tau_v dGamma/dt). Loaded fast against tau_r it is a spring: the modulus rises to
// (1 + beta) E_b and no further. That bound is why this form, and not a bare Kelvin-Voigt dashpot,
// is used: the dashpot damps the network's highest mode with a ratio tau_v omega_max / 2 (tens at
// tau_v = 2e-4 s), which an explicit step survives only at dt ~ 2 / (tau_v omega_max^2), two
// orders of magnitude below the elastic step; the arm needs only dt / sqrt(1 + beta).
//
// Over one step of length dt, with Gamma linear in time, the update is exact:
//   h(t + dt) = a h(t) + beta (1 - a) (tau_r / dt) (Gamma(t + dt) - Gamma(t)),   a = exp(-dt / tau_r);
// the gain beta (1 - a) tau_r / dt never exceeds beta, so the step sees at most (1 + beta) E_b, for
// any tau_r against dt.
#include <cmath>

namespace shard::beam {

struct MaxwellArm {
  double decay = 1;  // a = exp(-dt / tau_r)
  double gain = 0;   // beta (1 - a) tau_r / dt

  MaxwellArm(double viscosity_time, double modulus_ratio, double dt) {
    if (!(viscosity_time > 0) || !(dt > 0)) return;
    const double relaxation = viscosity_time / modulus_ratio;
    const double x = dt / relaxation;
    decay = std::exp(-x);
    gain = modulus_ratio * -std::expm1(-x) / x;  // (1 - a) / x without cancellation at small x
  }

  double advance(double arm_strain, double strain_increment) const { return decay * arm_strain + gain * strain_increment; }
};

}  // namespace shard::beam
