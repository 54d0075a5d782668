#pragma once
// The damping ratio that makes the linear spring-dashpot realise a set restitution.
//
// A contact pushes and never pulls, so the force max(0, k delta + gamma d(delta)/dt) lets go
// before the overlap returns to zero, once the dashpot outweighs the spring. The classical
// e = exp(-pi zeta / sqrt(1 - zeta^2)) ignores this and underestimates the damping needed
// (Schwager & Poeschel 2007: for e = 0.5 it gives zeta = 0.215, the exact value is 0.255).
// The free oscillator m x'' = -k x - gamma x', x(0) = 0, x'(0) = v0 has closed-form solutions; the contact ends when k x + gamma x' = 0 and the particles leave
// with the speed they have then. That e(zeta) depends on zeta alone and is inverted by bisection.

namespace shard::linear {

// Realised restitution for damping ratio zeta = gamma / (2 sqrt(k m*)) >= 0, closed form.
double restitution_for_damping_ratio(double zeta);

// The zeta with restitution_for_damping_ratio(zeta) == e, for 0 < e <= 1 (bisection to 1e-14 of zeta).
double damping_ratio_for_restitution(double e);

}  // namespace shard::linear
