#pragma once
// Reference data of beam_bond, in the style of LAMMPS' unittest/force-styles: per case a small
// TOML file (plugins/bond/beam_bond/reference/<case>.toml) holding a fixed random configuration
// of bonded pairs (positions, orientations, velocities, spins, radii, masses, inertias, stable
// ids), the plugin's parameters, and for each of a few deformation steps the forces, torques,
// energies, break decisions and break stresses the plugin computed. test_bond_beam_reference
// recomputes them through the loaded plugin and compares; beam_bond_reference_gen writes them
// (docs/how-to/write-a-plugin.md, "Reference data"). The configuration is stored, not re-drawn, so the check
// does not depend on the standard library's random distributions.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bond_pair.hpp"
#include "shard/params.hpp"

namespace shard::test {

// One case: a name (the file's), what it exercises, and the plugin parameters that differ from
// the schema's defaults.
struct ReferenceCase {
  std::string name;
  std::string description;
  std::map<std::string, ParamValue> params;
};

// Plain beam_bond and one case per effect policy, each alone (damping on, so the rate paths count).
inline std::vector<ReferenceCase> beam_reference_cases() {
  const std::map<std::string, ParamValue> base{{"damping", 1e-3}, {"rotational_damping", 0.5}};
  auto with = [&](std::map<std::string, ParamValue> extra) {
    std::map<std::string, ParamValue> p = base;
    for (auto& [k, v] : extra) p[k] = v;
    return p;
  };
  return {
      {"plain", "beam_bond with Table I defaults, eq. 4 damping 1e-3 N s/m, half the eq. 6 damping", base},
      {"weibull_strength", "per-bond Weibull strength, m = 4, seed 11", with({{"strength_weibull_modulus", 4.0},
                                                                             {"strength_seed", 11.0}})},
      {"softening", "linear softening, ratio 2 (damage carried from step to step)", with({{"softening_ratio", 2.0}})},
      {"viscosity", "standard linear solid: Maxwell arm, tau_v = 2 steps, beta = 1.5 (arm state carried)",
       with({{"viscosity_time", 2e-6}, {"viscous_modulus_ratio", 1.5}})},
      {"compression_asymmetry", "axial stiffness in compression 3 x that in tension",
       with({{"compression_stiffness_ratio", 3.0}})},
  };
}

// The configuration of one step (particles only; the bonds and sizes are fixed) and what the
// plugin returned for each bond.
struct ReferenceStep {
  std::vector<Vec3> position, velocity, omega;
  std::vector<Quat> orientation;
  std::vector<Vec3> force, torque_i, torque_j;
  std::vector<double> energy, sigma_vm;  // sigma_vm: the stress at failure, 0 for an intact bond
  std::vector<int> broken;
};

struct ReferenceData {
  std::string model = "beam_bond";
  std::string description;
  std::map<std::string, ParamValue> params;
  double dt = 0;
  HandBonds bonded;  // particles as bonded (the reference configuration) and the bond list
  std::vector<ReferenceStep> steps;
};

// File I/O (beam_reference.cpp).
void write_reference(const std::string& path, const ReferenceData& data);
ReferenceData read_reference(const std::string& path);  // throws naming the file and key

// Copies a step's particle configuration into the scene (outputs untouched).
inline void apply(const ReferenceStep& step, HandBonds& s) {
  s.position = step.position;
  s.velocity = step.velocity;
  s.omega = step.omega;
  s.orientation = step.orientation;
}

}  // namespace shard::test
