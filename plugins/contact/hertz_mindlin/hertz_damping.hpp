#pragma once
// The dashpot coefficient that makes the Hertz contact realise a set coefficient of restitution.
//
// With F = max(0, 4/3 E* sqrt(R*) delta^1.5 + c sqrt(S_n m*) d(delta)/dt), S_n = 2 E* sqrt(R* delta),
// scaling delta by the impact speed v0 and the Hertz time (m*^2 / (k^2 v0))^(1/5) turns the head-on
// collision into one parameter-free equation for the dimensionless overlap y(s):
//     y'' = -max(0, y^1.5 + c sqrt(3/2) y^0.25 y'),   y(0) = 0, y'(0) = 1,
// and the restitution is e = -y' when y returns to zero. Hence e depends on c alone, not on the
// impact speed, material or size. The textbook c = 2 sqrt(5/6) beta(e) linearises this equation
// and, with the clamp, realises 0.55 for a set 0.5, so the model solves the equation numerically
// once, at construction. RK4 at h = 2e-4 agrees with h = 2e-5 to 1e-6 in e.

namespace shard::hertz {

// Restitution realised by the dimensionless collision above for damping c >= 0 (RK4, step h).
double restitution_for_damping(double c, double h = 2e-4);

// The c >= 0 with restitution_for_damping(c) == e, for 0 < e <= 1 (bisection to 1e-12 of c).
double damping_for_restitution(double e);

}  // namespace shard::hertz
