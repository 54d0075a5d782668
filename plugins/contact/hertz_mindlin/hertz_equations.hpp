#pragma once
// Hertz-Mindlin contact of two spheres (README.md), one equation each.
// Symbols: E Young's modulus, G shear modulus, nu Poisson's ratio, R* effective radius,
// delta overlap, m* effective mass. A wall has infinite radius (the kernel passes R* = r,
// m* = m); with one material it is taken to be of the particles' material, so the same E* and G*
// serve particle-wall contacts; with several, of its own (the mixed forms below).
#include <cmath>
#include <numbers>

namespace shard::hertz {

inline double young_modulus(double G, double nu) { return 2.0 * G * (1.0 + nu); }

// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 with both bodies alike.
inline double effective_young_modulus(double E, double nu) { return E / (2.0 * (1.0 - nu * nu)); }

// 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2 with both bodies alike.
inline double effective_shear_modulus(double G, double nu) { return G / (2.0 * (2.0 - nu)); }

// F_n = 4/3 E* sqrt(R*) delta^1.5
inline double normal_elastic_force(double E_star, double R, double delta) {
  return 4.0 / 3.0 * E_star * std::sqrt(R) * delta * std::sqrt(delta);
}

// Two materials (docs/reference/materials.md; Johnson, Contact Mechanics, 1985, eq. 4.22 for E*; Mindlin
// 1949 as in Di Renzo and Di Maio, Chem. Eng. Sci. 59 (2004) 525, for G*): a wall's material
// against the particles', or two kinds of particles.
// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
inline double mixed_young_modulus(double E1, double nu1, double E2, double nu2) {
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
}

// 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2
inline double mixed_shear_modulus(double G1, double nu1, double G2, double nu2) {
  return 1.0 / ((2.0 - nu1) / G1 + (2.0 - nu2) / G2);
}

// S_n = dF_n/d delta = 2 E* sqrt(R* delta)
inline double normal_stiffness(double E_star, double R, double delta) {
  return 2.0 * E_star * std::sqrt(R * delta);
}

// S_t = 8 G* sqrt(R* delta)  (Mindlin, no slip)
inline double tangential_stiffness(double G_star, double R, double delta) {
  return 8.0 * G_star * std::sqrt(R * delta);
}

// Dashpot coefficient c sqrt(S m*), N s/m; c is the dimensionless damping from restitution.
inline double dashpot(double c, double stiffness, double m) { return c * std::sqrt(stiffness * m); }

// U_n = integral of F_n d delta = 8/15 E* sqrt(R*) delta^2.5
inline double normal_elastic_energy(double E_star, double R, double delta) {
  return 8.0 / 15.0 * E_star * std::sqrt(R) * delta * delta * std::sqrt(delta);
}

// Rayleigh wave time across the smallest sphere (seed eq. 11, docs/explanation/physics.md "Time step"):
// t_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766)
inline double rayleigh_time(double R, double rho, double G, double nu) {
  return std::numbers::pi * R * std::sqrt(rho / G) / (0.1631 * nu + 0.8766);
}

// Textbook estimate of c (the EDEM form 2 sqrt(5/6) beta, beta from the linear oscillator). With
// the no-pull clamp it realises e = 0.55 for a set 0.5 and 0.25 for a set 0.1, so the model uses
// the exact value from hertz_damping.hpp and keeps this only for comparison.
inline double textbook_damping(double e) {
  const double log_e = std::log(e);
  return -2.0 * std::sqrt(5.0 / 6.0) * log_e / std::sqrt(log_e * log_e + std::numbers::pi * std::numbers::pi);
}

}  // namespace shard::hertz
