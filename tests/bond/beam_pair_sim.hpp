#pragma once
// A free bonded pair of Table I spheres run by the kernel's Simulation, excited in one beam mode,
// with the theory of that mode (reduced mass / reduced inertia of two equal spheres).
#include <cmath>
#include <numbers>
#include <vector>

#include "beam_setup.hpp"
#include "shard/simulation.hpp"

namespace shard::test {

enum class Mode { Axial, Shear, Twist, Bending };

inline const char* name_of(Mode m) {
  switch (m) {
    case Mode::Axial: return "axial";
    case Mode::Shear: return "shear";
    case Mode::Twist: return "twist";
    case Mode::Bending: return "bending";
  }
  return "?";
}

inline const Vec3 kPairAxis = Vec3(1, 2, -0.5).normalized();
inline const Vec3 kPairSide = kPairAxis.cross(Vec3(0.2, -0.3, 1.0)).normalized();

inline SimulationSetup pair_setup(const BondModel& model) {
  SimulationSetup s;
  const Vec3 centre(0.01, -0.02, 0.003);
  s.particles.add(centre - kRadius * kPairAxis, kRadius, kDensity);
  s.particles.add(centre + kRadius * kPairAxis, kRadius, kDensity);
  s.particles.orientation[0] = rotation(Vec3(0.3, -1.1, 0.7));
  s.particles.orientation[1] = rotation(Vec3(-2.0, 0.4, 0.9));
  s.bonds = {{0, 1}};
  s.bond = &model;
  s.dt = 0;  // auto: eq. 12
  s.record_bond_loads = true;  // the tests read the bond's force and torques
  return s;
}

// Starts the pair in its bonded state with the velocities of one mode, so the kernel's forces at
// construction are right; amplitudes of strain 1e-4 or relative rotation 1e-3 rad. Every mode
// starts with zero momentum and zero angular momentum.
inline void excite(Particles& p, Mode mode, double l0, double omega, double m, double I) {
  const double strain = 1e-4, angle = 1e-3;
  const Vec3 bend_axis = kPairAxis.cross(kPairSide);  // turns the axis towards the side
  switch (mode) {
    case Mode::Axial:
      p.velocity[1] = 0.5 * omega * strain * l0 * kPairAxis;
      p.velocity[0] = -p.velocity[1];
      break;
    case Mode::Shear: {
      // s = offset / l0 - phi with L = m_r l0 offset' + 2 I phi' = 0 about bend_axis.
      const double m_r = m / 2;
      const double offset_rate = omega * strain / (1 / l0 + m_r * l0 / (2 * I));
      p.velocity[1] = 0.5 * offset_rate * kPairSide;
      p.velocity[0] = -p.velocity[1];
      p.omega[0] = p.omega[1] = -m_r * l0 * offset_rate / (2 * I) * bend_axis;
      break;
    }
    case Mode::Twist:
      p.omega[1] = 0.5 * omega * angle * kPairAxis;
      p.omega[0] = -p.omega[1];
      break;
    case Mode::Bending:
      p.omega[1] = 0.5 * omega * angle * bend_axis;
      p.omega[0] = -p.omega[1];
      break;
  }
}

// The bond's load in the mode: a force or moment proportional to the modal coordinate.
inline double modal_signal(const Simulation& sim, Mode mode) {
  const Bonds& b = sim.bonds();
  switch (mode) {
    case Mode::Axial: return b.force[0].dot(kPairAxis);
    case Mode::Shear: return b.force[0].dot(kPairSide);
    case Mode::Twist: return b.torque_i[0].dot(kPairAxis);
    case Mode::Bending: return b.torque_i[0].dot(kPairAxis.cross(kPairSide));
  }
  return 0;
}

// Stiffness and inertia of the mode's relative coordinate for two equal spheres.
//  axial:   m_r x'' = -(E A / l0) x,  m_r = m / 2
//  twist:   I_r t'' = -(2 G J / l0) t, I_r = I / 2 (eq. 7)
//  bending: I_r t'' = -(E J / l0) t   (opposite end rotations, the bond line stays put)
//  shear:   the lateral offset d and the common rotation phi share s = d / l0 - phi; with the
//           couple split equally, m_r d'' = -K_s l0 s and I phi'' = K_s l0^2 s / 2, so
//           s'' = -K_s (1 / m_r + l0^2 / (2 I)) s,  K_s = a_s G A / l0.
struct ModeTheory {
  double stiffness, inertia;  // of the modal coordinate
  double omega() const { return std::sqrt(stiffness / inertia); }
  double period() const { return 2 * std::numbers::pi / omega(); }
};

inline ModeTheory theory_of(Mode mode, const BeamNumbers& b, double m, double I) {
  switch (mode) {
    case Mode::Axial: return {b.axial(), m / 2};
    case Mode::Shear: return {b.shear(), 1.0 / (2 / m + b.l0 * b.l0 / (2 * I))};
    case Mode::Twist: return {b.twist(), I / 2};
    case Mode::Bending: return {b.bending(), I / 2};
  }
  return {1, 1};
}

// Upward zero crossings of a sampled signal, linearly interpolated, in units of the sample index.
inline std::vector<double> upward_crossings(const std::vector<double>& s) {
  std::vector<double> at;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (s[k - 1] < 0 && s[k] >= 0) at.push_back(static_cast<double>(k - 1) + s[k - 1] / (s[k - 1] - s[k]));
  return at;
}

// Heights of the local maxima, refined by a parabola through the three samples around each.
inline std::vector<double> peak_heights(const std::vector<double>& s) {
  std::vector<double> peaks;
  for (std::size_t k = 1; k + 1 < s.size(); ++k) {
    if (s[k] > s[k - 1] && s[k] >= s[k + 1] && s[k] > 0) {
      const double a = s[k - 1], b = s[k], c = s[k + 1];
      const double denom = a - 2 * b + c;
      peaks.push_back(denom < 0 ? b - (a - c) * (a - c) / (8 * denom) : b);
    }
  }
  return peaks;
}

}  // namespace shard::test
