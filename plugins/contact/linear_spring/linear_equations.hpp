#pragma once
// Linear spring-dashpot contact (README.md, the cheap baseline), one equation each.
// Symbols: k_n, k_t normal and tangential stiffness, zeta damping ratio, m* effective mass.
#include <cmath>
#include <numbers>

namespace shard::linear {

// F_n = k_n delta
inline double normal_elastic_force(double k_n, double delta) { return k_n * delta; }

// gamma = 2 zeta sqrt(k m*): the dashpot that gives the oscillator k, m* the damping ratio zeta.
inline double dashpot(double zeta, double k, double m) { return 2.0 * zeta * std::sqrt(k * m); }

// U = 1/2 k_n delta^2
inline double normal_elastic_energy(double k_n, double delta) { return 0.5 * k_n * delta * delta; }

// Duration of an undamped contact of effective mass m*: half the oscillator period.
inline double contact_duration(double k, double m) { return std::numbers::pi * std::sqrt(m / k); }

// A sphere's contact point resists tangential motion with mass m / (1 + m r^2 / I) = m / 3.5
// (translation plus rolling), so the tangential spring oscillates as fast as a normal spring
// 3.5 k_t stiff. With k_t = 2/7 k_n both periods are equal.
inline double stiffest_oscillator(double k_n, double k_t) { return std::fmax(k_n, 3.5 * k_t); }

}  // namespace shard::linear
