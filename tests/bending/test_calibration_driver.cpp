// The calibration driver on model functions standing in for the bending runs: it must reach the
// targets within tolerance in few runs, follow a drifting E, cope with unbroken runs and say so
// when a target is out of reach.
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>

#include "shard/bending/calibration.hpp"

using namespace shard::bending;

namespace {

// A beam whose E grows slightly sub-linearly with E_b (contacts do not scale with E_b), and whose
// F_max grows with sigma_crit^0.9 and a little with E_b; damage before the fit window softens E
// by 2 % when breakage is on.
struct ModelBeam {
  int calls = 0;
  CalibrationRun operator()(double e_b, double sigma, bool breakage, const std::string&, int) {
    ++calls;
    CalibrationRun r;
    r.youngs_modulus = 0.62 * e_b * std::pow(e_b / 12.8e6, -0.05) * (breakage ? 0.98 : 1.0);
    r.force_max = 60.0 * std::pow(sigma / 0.24e6, 0.9) * std::pow(e_b / 12.8e6, 0.1);
    r.failed = breakage;
    return r;
  }
};

}  // namespace

TEST_CASE("calibration reaches E and F_max within 3 % on a model beam") {
  ModelBeam beam;
  CalibrationTargets t;
  t.youngs_modulus = 13.2e6;
  t.force_max = 45.0;
  int observed = 0;
  const auto r = calibrate(t, 12.8e6, 0.24e6, std::ref(beam), [&](const CalibrationRun&) { ++observed; });
  REQUIRE(r.converged);
  CHECK(observed == beam.calls);
  CHECK(static_cast<int>(r.runs.size()) <= 20);
  CHECK(r.runs.size() <= 8);  // secant steps on near power laws converge in a handful of runs
  const auto& last = r.runs.back();
  CHECK(std::abs(last.youngs_modulus / 13.2e6 - 1) <= 0.03);
  CHECK(std::abs(last.force_max / 45.0 - 1) <= 0.03);
  CHECK(last.breakage);
  CHECK(r.runs.front().stage == "stiffness");
  CHECK_FALSE(r.runs.front().breakage);
  // The final parameters are those of the last run.
  CHECK(r.bond_youngs_modulus == last.bond_youngs_modulus);
  CHECK(r.bond_critical_stress == last.bond_critical_stress);
  // The CSV holds a header and one line per run.
  std::istringstream csv(calibration_csv(r));
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  CHECK(lines == static_cast<int>(r.runs.size()) + 1);
}

TEST_CASE("calibration: runs that do not break weaken the bonds until they do") {
  CalibrationTargets t;
  t.youngs_modulus = 8e6;
  t.force_max = 30.0;
  auto beam = [](double e_b, double sigma, bool breakage, const std::string&, int) {
    CalibrationRun r;
    r.youngs_modulus = 0.6 * e_b;
    const double strength = 100.0 * sigma / 1e6;  // N
    const double reach = 40.0;                    // the run stops at 40 N whatever happens
    r.failed = breakage && strength < reach;
    r.force_max = breakage ? std::min(strength, reach) : reach;
    return r;
  };
  const auto r = calibrate(t, 12.8e6, 2.0e6, beam);  // 200 N strength: no break at first
  REQUIRE(r.converged);
  CHECK(r.bond_critical_stress == doctest::Approx(0.3e6).epsilon(0.03));
}

TEST_CASE("calibration reports a target out of reach instead of pretending") {
  CalibrationTargets t;
  t.youngs_modulus = 13.2e6;
  t.max_runs = 6;
  // E saturates at 5 MPa whatever E_b: the target cannot be met.
  auto beam = [](double e_b, double, bool, const std::string&, int) {
    CalibrationRun r;
    r.youngs_modulus = 5e6 * e_b / (e_b + 1e6);
    return r;
  };
  const auto r = calibrate(t, 12.8e6, 0.24e6, beam);
  CHECK_FALSE(r.converged);
  CHECK(r.runs.size() == 6);
  CHECK(r.message.find("did not reach") != std::string::npos);
}

TEST_CASE("secant update: exact for a power law after two points") {
  const std::vector<double> x{1.0, 2.0}, y{3.0, 3.0 * std::pow(2.0, 0.7)};
  const double next = secant_update(x, y, 3.0 * std::pow(3.0, 0.7));
  CHECK(next == doctest::Approx(3.0).epsilon(1e-12));
  // One point: proportional step.
  CHECK(secant_update({2.0}, {4.0}, 6.0) == doctest::Approx(3.0));
  // Clamped to a factor of 5.
  CHECK(secant_update({1.0}, {1.0}, 100.0) == doctest::Approx(5.0));
}
