#pragma once
// Calibration of the bond parameters on the four-point bending test (seed sec. V.2-3):
//  1. stiffness: breakage off, E_b is adjusted until the test's E (eq. 14 on the fitted initial
//     stiffness) matches the target;
//  2. strength: breakage on, sigma_crit is adjusted until F_max matches; should E leave its
//     tolerance on the way (damage before 40 % of F_max), E_b is corrected in the same run.
// Each parameter is updated by a secant step in log-log space, y ~ x^p with p from the last two
// runs (p = 1 at the first step: the elastic response is linear in E_b, and a brittle beam's
// F_max is linear in the bond strength), clamped to [0.2, 5] and to a factor of 5 per step.
// The runs themselves are a callback, so the driver is tested on a model function and run on
// `shard run` by `shard calibrate`.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shard/io/json.hpp"

namespace shard::bending {

struct CalibrationTargets {
  double youngs_modulus = 13.2e6;    // Pa, E by eq. 14 (seed: 13.2 MPa)
  std::optional<double> force_max;   // N; none: stiffness only
  double tolerance = 0.03;           // relative, for E and F_max
  int max_runs = 20;
};

struct CalibrationRun {
  int index = 0;                 // 1-based
  std::string stage;             // "stiffness" or "strength"
  double bond_youngs_modulus = 0, bond_critical_stress = 0;  // Pa, what was run
  bool breakage = false;
  double youngs_modulus = 0;     // Pa, measured E (eq. 14)
  double force_max = 0;          // N, measured
  bool failed = false;           // the beam broke (force dropped after the peak)
  double wall_seconds = 0;
  std::string output;            // where the run wrote its files
  std::string note;
};

struct CalibrationResult {
  std::vector<CalibrationRun> runs;
  double bond_youngs_modulus = 0, bond_critical_stress = 0;  // final parameters, Pa
  bool converged = false;
  std::string message;
};

// Runs one test with these bond parameters and fills the measured fields of the returned run.
using CalibrationEvaluate = std::function<CalibrationRun(double bond_youngs_modulus, double bond_critical_stress,
                                                         bool breakage, const std::string& stage, int index)>;
// Called after every run (to print and store it as it comes).
using CalibrationObserver = std::function<void(const CalibrationRun&)>;

CalibrationResult calibrate(const CalibrationTargets& targets, double initial_youngs_modulus,
                            double initial_critical_stress, const CalibrationEvaluate& evaluate,
                            const CalibrationObserver& observer = {});

// One secant update in log space: returns the next x for target y given the history (x_k, y_k).
double secant_update(const std::vector<double>& x, const std::vector<double>& y, double target);

std::string calibration_csv(const CalibrationResult& r);
// The targets, the outcome and every run as a JSON document (shard/io/json.hpp); format version 1.
inline constexpr int kCalibrationFormat = 1;
io::Json calibration_json(const CalibrationResult& r, const CalibrationTargets& targets);

}  // namespace shard::bending
