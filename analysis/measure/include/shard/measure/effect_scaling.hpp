#pragma once
// Plausible effect sizes from the scene, not from one test beam.
//
// An effect's `plausible` size is the trial run whose difference from the base is its signature,
// and the signature must stand above the packing noise without leaving the range where the
// effect acts linearly. A dimensionless size (a Weibull modulus, a softening or compression
// stiffness ratio, a friction coefficient) is already relative to the scene's own bond and
// contact laws. A size with a unit of the test is not: 1e-4 m/N of machine compliance is a
// quarter of the tiny beam's secant compliance w_peak / F_max (~4e-4 m/N) but all of the default
// beam's (4.96 mm / 49 N), and 1 ms of bond viscosity is a tenth of the tiny beam's time to peak
// at 0.1 m/s but 0.05 % of the default beam's at 2.5 mm/s (2 s). The rule (docs/explanation/diagnosis.md
// "Candidate effects"):
//
//   an effect with a unit of the test names its scale in the library (plausible_from,
//   plausible_factor, effect_library.hpp), and the commands resolve it from the scene's base run:
//   the fitted base model, run as the lab ran the test (its rates, ramp, preload), on the
//   packing seeds of the study. machine_compliance: a fraction of the base run's secant
//   compliance w_peak / F_max (the specimen's own); bond_viscosity: a fraction of its time to
//   peak at the fastest rate (a relaxation time that shows within the test).
//
// Every command resolves them on the model's base run: the contrast commands (diagnose-sets,
// calibrate-contrast) on the base fitted to the reference, diagnose and calibrate-effect on the
// base at the scene's values (plausible_on_base_run, diagnosis_step.hpp). The shipped
// library uses both rules (scenes/measurements/effects.toml).
#include <string>
#include <vector>

#include "shard/measure/curve.hpp"
#include "shard/measure/effect_library.hpp"

namespace shard::measure {

// The test scales of simulated curves, one group per loading rate (model time: no time
// compression). Throws std::invalid_argument when there is no curve.
TestScales base_run_scales(const std::vector<std::vector<Curve>>& curves_by_rate);

// The effects whose plausible size follows a rule, one line each: "machine_compliance 1.02e-04
// m/N = 0.1 x secant_compliance 1.02e-03 (the base run)". Empty when no effect has a rule.
std::string describe_scaled_plausible(const std::vector<CandidateEffect>& effects, const TestScales& scales);

}  // namespace shard::measure
