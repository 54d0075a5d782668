#include "shard/bending/calibration.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shard::bending {
namespace {

bool within(double value, double target, double tolerance) {
  return std::abs(value / target - 1.0) <= tolerance;
}

}  // namespace

double secant_update(const std::vector<double>& x, const std::vector<double>& y, double target) {
  if (x.empty() || x.size() != y.size()) throw std::invalid_argument("secant_update: empty or mismatched history");
  const double xn = x.back(), yn = y.back();
  if (!(xn > 0 && yn > 0 && target > 0)) throw std::invalid_argument("secant_update: needs positive values");
  double p = 1.0;
  if (x.size() >= 2) {
    const double xm = x[x.size() - 2], ym = y[y.size() - 2];
    const double dx = std::log(xn / xm), dy = std::log(yn / ym);
    if (std::abs(dx) > 1e-9 && ym > 0) p = std::clamp(dy / dx, 0.2, 5.0);
  }
  const double factor = std::clamp(std::pow(target / yn, 1.0 / p), 0.2, 5.0);
  return xn * factor;
}

CalibrationResult calibrate(const CalibrationTargets& t, double e_b, double sigma, const CalibrationEvaluate& evaluate,
                            const CalibrationObserver& observer) {
  if (!(t.youngs_modulus > 0)) throw std::invalid_argument("calibrate: the target E must be positive");
  if (t.force_max && !(*t.force_max > 0)) throw std::invalid_argument("calibrate: the target F_max must be positive");
  if (!(e_b > 0 && sigma > 0)) throw std::invalid_argument("calibrate: the initial bond parameters must be positive");
  CalibrationResult r;
  auto run = [&](const std::string& stage, bool breakage) {
    CalibrationRun c = evaluate(e_b, sigma, breakage, stage, static_cast<int>(r.runs.size()) + 1);
    c.index = static_cast<int>(r.runs.size()) + 1;
    c.stage = stage;
    c.bond_youngs_modulus = e_b;
    c.bond_critical_stress = sigma;
    c.breakage = breakage;
    r.runs.push_back(c);
    if (observer) observer(c);
    return c;
  };

  // Stage 1: stiffness with breakage off. Aim at half the tolerance so stage 2 starts with margin.
  std::vector<double> xe, ye;
  bool stiff = false;
  while (static_cast<int>(r.runs.size()) < t.max_runs) {
    const auto c = run("stiffness", false);
    if (!(c.youngs_modulus > 0)) throw std::runtime_error(fmt::format("calibration run {}: no stiffness measured", c.index));
    xe.push_back(e_b);
    ye.push_back(c.youngs_modulus);
    if (within(c.youngs_modulus, t.youngs_modulus, 0.5 * t.tolerance)) {
      stiff = true;
      break;
    }
    e_b = secant_update(xe, ye, t.youngs_modulus);
  }
  if (!stiff) {
    r.message = fmt::format("E did not reach {:.4g} MPa within {} runs", 1e-6 * t.youngs_modulus, t.max_runs);
    r.bond_youngs_modulus = e_b, r.bond_critical_stress = sigma;
    return r;
  }
  if (!t.force_max) {
    r.converged = true;
    r.message = "stiffness calibrated (no strength target)";
    r.bond_youngs_modulus = e_b, r.bond_critical_stress = sigma;
    return r;
  }

  // Stage 2: strength with breakage on; E_b follows if E drifts.
  std::vector<double> xs, ys;
  while (static_cast<int>(r.runs.size()) < t.max_runs) {
    const auto c = run("strength", true);
    const bool e_ok = within(c.youngs_modulus, t.youngs_modulus, t.tolerance);
    const bool f_ok = c.failed && within(c.force_max, *t.force_max, t.tolerance);
    if (e_ok && f_ok) {
      r.converged = true;
      r.message = fmt::format("E and F_max within {:.1f} % after {} runs", 100 * t.tolerance, r.runs.size());
      r.bond_youngs_modulus = e_b, r.bond_critical_stress = sigma;
      return r;
    }
    if (!e_ok) {
      xe.push_back(e_b);
      ye.push_back(c.youngs_modulus);
      e_b = secant_update(xe, ye, t.youngs_modulus);
    }
    if (!c.failed) {
      // The beam did not break within the run: F_max is only a lower bound of the strength, so
      // no secant step; the bonds are weakened until it breaks.
      sigma *= std::clamp(*t.force_max / std::max(c.force_max, 1e-300), 0.3, 0.7);
      xs.clear(), ys.clear();
      continue;
    }
    if (!within(c.force_max, *t.force_max, t.tolerance)) {
      xs.push_back(sigma);
      ys.push_back(c.force_max);
      sigma = secant_update(xs, ys, *t.force_max);
    }
  }
  r.message = fmt::format("not converged within {} runs", t.max_runs);
  r.bond_youngs_modulus = e_b, r.bond_critical_stress = sigma;
  return r;
}

std::string calibration_csv(const CalibrationResult& r) {
  std::string s =
      "run,stage,bond_youngs_modulus_Pa,bond_critical_stress_Pa,breakage,youngs_modulus_Pa,force_max_N,failed,"
      "wall_seconds,output,note\n";
  for (const auto& c : r.runs)
    s += fmt::format("{},{},{:.9g},{:.9g},{},{:.9g},{:.9g},{},{:.3f},{},{}\n", c.index, c.stage, c.bond_youngs_modulus,
                     c.bond_critical_stress, c.breakage, c.youngs_modulus, c.force_max, c.failed, c.wall_seconds, c.output,
                     c.note);
  return s;
}

io::Json calibration_json(const CalibrationResult& r, const CalibrationTargets& t) {
  io::Json j = io::json_document(kCalibrationFormat);
  j["target_youngs_modulus_Pa"] = t.youngs_modulus;
  j["target_force_max_N"] = t.force_max ? io::Json(*t.force_max) : io::Json(nullptr);
  j["tolerance"] = t.tolerance;
  j["converged"] = r.converged;
  j["message"] = r.message;
  j["bond_youngs_modulus_Pa"] = r.bond_youngs_modulus;
  j["bond_critical_stress_Pa"] = r.bond_critical_stress;
  j["runs"] = io::Json::array();
  for (const auto& c : r.runs)
    j["runs"].push_back({{"run", c.index},
                         {"stage", c.stage},
                         {"bond_youngs_modulus_Pa", c.bond_youngs_modulus},
                         {"bond_critical_stress_Pa", c.bond_critical_stress},
                         {"breakage", c.breakage},
                         {"youngs_modulus_Pa", c.youngs_modulus},
                         {"force_max_N", c.force_max},
                         {"failed", c.failed},
                         {"wall_seconds", c.wall_seconds},
                         {"output", c.output}});
  return j;
}

}  // namespace shard::bending
