#pragma once
// The seed's filter-cake material (seed Table I, docs/explanation/physics.md) and hand-written reference formulas:
// the tests compute expected values here, independently of the plugin sources.
#include <cmath>
#include <numbers>

namespace shard::test::table_one {

inline constexpr double density = 3720.0;        // kg/m^3
inline constexpr double shear_modulus = 10e6;    // Pa
inline constexpr double poisson_ratio = 0.25;    // 1 (our choice; the seed gives none)
inline constexpr double friction = 0.67;         // 1
inline constexpr double radius = 0.35e-3;        // m (d = 0.7 mm)

inline double sphere_mass(double r, double rho = density) { return rho * 4.0 / 3.0 * std::numbers::pi * r * r * r; }

// E* for two bodies of one material: 1/E* = 2 (1 - nu^2) / E, E = 2 G (1 + nu).
inline double e_star(double G = shear_modulus, double nu = poisson_ratio) {
  return 2.0 * G * (1.0 + nu) / (2.0 * (1.0 - nu * nu));
}
// G* for two bodies of one material: 1/G* = 2 (2 - nu) / G.
inline double g_star(double G = shear_modulus, double nu = poisson_ratio) { return G / (2.0 * (2.0 - nu)); }

// Duration of an elastic Hertz impact at speed v (Johnson, Contact Mechanics, eq. 11.24):
// t = 2.868 (m*^2 / (R* E*^2 v))^(1/5).
inline double hertz_contact_duration(double m_eff, double r_eff, double E_star, double v) {
  return 2.868 * std::pow(m_eff * m_eff / (r_eff * E_star * E_star * v), 0.2);
}

}  // namespace shard::test::table_one
