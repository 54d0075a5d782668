// ContrastStudy::calibrate_base: the base parameters fitted to the reference by Gauss-Newton on
// standardised targets (contrast_study.hpp, BaseCalibration).
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <ostream>

#include "shard/measure/contrast_study.hpp"
#include "shard/measure/rate_groups.hpp"
#include "shard/measure/statistics.hpp"

namespace shard::measure {
namespace {

constexpr double kBaseStep = 0.05;  // relative step of a base parameter for its Jacobian
constexpr double kConvergedStep = 0.005;  // in log: a step this small ends the fit
// Targets: the reference's (or the consensus') logarithms of stiffness, peak force and peak
// displacement, the form-free scale of a curve. They hold about two independent numbers (w_peak
// follows from the other two for a nearly linear rise), enough for E_b and sigma_crit; a third
// parameter moves the form (bond.poisson_ratio: the bond's shear-to-normal stiffness), and the
// fit then also asks the post-peak regime of the curve (the comparison's mean standardised
// residual after the peak, to the end of the shortest measured curve) to vanish.
constexpr std::size_t kScaleTargets = 3;

struct BaseTargets {
  std::vector<double> target;    // components: the median of the reference groups' means
  std::vector<double> u_target;  // the scale targets' standard uncertainties
  std::vector<Specimen> reference;  // the specimens at the scale rate the form is compared with
  const Metadata* metadata = nullptr;
  bool form = false;  // the post-peak regime is a target too
};

// The reference's components with each curve's own elastic window (contrast_components without a
// band), the window the simulated base is scored with: the base and the reference share their
// peak, so the own window compares like with like, and the study's band serves the contrasts
// between batches of different strength.
std::vector<double> own_window_mean(const ContrastSets& sets, const ContrastGroup& g) {
  std::vector<std::vector<double>> rows;
  for (const auto& sp : sets.sets[g.set].specimens)
    if (same_rate(sp.loading_rate, g.rate)) rows.push_back(contrast_components(sp.curve));
  return component_mean(rows);
}

BaseTargets base_targets(const ContrastSets& sets, const std::vector<ContrastGroup>& groups,
                         const GroupScatter& scatter, double scale_rate, bool form) {
  BaseTargets t;
  t.form = form;
  t.metadata = &sets.sets[sets.reference.value_or(0)].metadata;
  std::vector<std::vector<double>> means, rows;
  // The reference's own scatter when it carries one (GroupScatter::own), else the pool's.
  const std::vector<std::vector<double>>* sigma = &scatter.pooled;
  for (std::size_t gi = 0; gi < groups.size(); ++gi) {
    const ContrastGroup& g = groups[gi];
    if (same_rate(g.rate, scale_rate) && (!sets.reference || g.set == *sets.reference)) {
      means.push_back(own_window_mean(sets, g));
      rows.insert(rows.end(), g.components.begin(), g.components.end());
      if (sets.reference) sigma = &scatter.covariance[gi];
    }
  }
  t.target = median_of(means);
  // Each scale target in units of its standard uncertainty: the specimen scatter over the
  // reference's specimens (the post-peak residual is standardised by the comparison itself).
  for (std::size_t i = 0; i < kScaleTargets; ++i)
    t.u_target.push_back(std::sqrt((*sigma)[i][i] / static_cast<double>(rows.size())));
  for (std::size_t k = 0; k < sets.sets.size(); ++k)
    if (!sets.reference || *sets.reference == k)
      for (const auto& sp : sets.sets[k].specimens)
        if (same_rate(sp.loading_rate, scale_rate)) t.reference.push_back(sp);
  return t;
}

// Standardised residuals of a model's runs; `band`: the comparison whose simulated band scores
// the post-peak regime (the base's, so that a step's difference is its mean's).
Eigen::VectorXd base_residual(const BaseTargets& t, const std::vector<Specimen>& sims, const Comparison* band,
                              Comparison& own) {
  std::vector<std::vector<double>> rows;
  for (const auto& s : sims) rows.push_back(contrast_components(s.curve));
  const std::vector<double> f = component_mean(rows);
  Eigen::VectorXd z(static_cast<Eigen::Index>(kScaleTargets + (t.form ? 1 : 0)));
  for (std::size_t i = 0; i < kScaleTargets; ++i) z(static_cast<Eigen::Index>(i)) = (f[i] - t.target[i]) / t.u_target[i];
  if (t.form) {
    own = compare(t.reference, *t.metadata, sims);
    const Comparison scored = band ? with_simulated_band(own, *band) : own;
    z(static_cast<Eigen::Index>(kScaleTargets)) = scored.regimes[static_cast<std::size_t>(Regime::PostPeak)].mean_residual;
  }
  return z;
}

std::string point_values(const BaseCalibration& cal) {
  std::string values;
  for (std::size_t i = 0; i < cal.keys.size(); ++i) values += fmt::format("{}{}={:.4g}", i ? ", " : "", cal.keys[i], cal.values[i]);
  return values;
}

// One line of the fit's path: the values and how far the model is from the reference.
std::string path_line(const BaseCalibration& cal, const Eigen::VectorXd& z, const BaseTargets& t) {
  const std::string values = point_values(cal);
  // z holds (model - target) / u: the relative error is exp(z u) - 1.
  return fmt::format("{}: stiffness {:+.1f} %, peak force {:+.1f} %, peak displacement {:+.1f} % against the reference{}",
                     values, 100 * std::expm1(z(0) * t.u_target[0]), 100 * std::expm1(z(1) * t.u_target[1]),
                     100 * std::expm1(z(2) * t.u_target[2]),
                     t.form ? fmt::format(", post-peak regime {:+.2f} sigma", z(3)) : "");
}

// The base at the given values.
ModelPlan point_model(const ModelPlan& base, const BaseCalibration& cal, double rate) {
  ModelPlan m = with_parameters(base, cal.keys, cal.values);
  m.loading_rate = rate;
  return m;
}

// For a Jacobian: each parameter 5 % up, or down where up leaves its range (poisson_ratio at
// 0.5); `steps` receives each one's step in log.
std::vector<ModelPlan> jacobian_models(const ModelPlan& base, const BaseCalibration& cal, double rate,
                                       std::vector<double>& steps) {
  const double log_step = std::log1p(kBaseStep);
  std::vector<ModelPlan> models;
  steps.assign(cal.keys.size(), log_step);
  for (std::size_t i = 0; i < cal.keys.size(); ++i) {
    std::vector<double> v = cal.values;
    v[i] *= 1 + kBaseStep;
    if (v[i] > cal.range[i].max) v[i] = cal.values[i] / (1 + kBaseStep), steps[i] = -log_step;
    models.push_back(with_parameters(base, cal.keys, v));
    models.back().loading_rate = rate;
  }
  return models;
}

Eigen::MatrixXd jacobian(const BaseTargets& t, const std::vector<std::vector<Specimen>>& sims,
                         const Comparison& base_comparison, const Eigen::VectorXd& z, const std::vector<double>& steps) {
  Eigen::MatrixXd J(z.size(), static_cast<Eigen::Index>(steps.size()));
  for (std::size_t i = 0; i < steps.size(); ++i) {
    Comparison unused;
    J.col(static_cast<Eigen::Index>(i)) = (base_residual(t, sims[i], &base_comparison, unused) - z) / steps[i];
  }
  return J;
}

// One Gauss-Newton step in the log-parameters, each kept in its range; returns the largest
// change made (in log).
double gauss_newton_step(BaseCalibration& cal, const Eigen::MatrixXd& J, const Eigen::VectorXd& z) {
  const Eigen::VectorXd step = J.colPivHouseholderQr().solve(-z);
  cal.at_bound.clear();
  double largest = 0;
  for (std::size_t i = 0; i < cal.keys.size(); ++i) {
    // A factor of two per iteration at most: a Jacobian taken 5 % away does not hold further.
    double s = step(static_cast<Eigen::Index>(i));
    if (std::abs(s) > std::log(2.0)) {
      s = std::copysign(std::log(2.0), s);
      cal.at_bound.push_back(cal.keys[i]);
    }
    const double previous = cal.values[i], asked = previous * std::exp(s);
    cal.values[i] = std::clamp(asked, cal.range[i].min, cal.range[i].max);
    cal.at_range_bound[i] = cal.values[i] != asked;
    largest = std::max(largest, std::abs(std::log(cal.values[i] / previous)));
  }
  return largest;
}

// Standard uncertainties from the last Jacobian: the targets are standardised, so the covariance
// of the log-parameters is (J'J)^-1 (Gauss-Newton's; the specimens' scatter of the reference, not
// the model's form error).
void set_uncertainties(BaseCalibration& cal, const Eigen::MatrixXd& J) {
  if (J.size() == 0) return;
  const Eigen::MatrixXd info = J.transpose() * J;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(info);
  if (!lu.isInvertible()) {
    cal.uncertainty.assign(cal.keys.size(), std::numeric_limits<double>::infinity());
    return;
  }
  const Eigen::MatrixXd cov = lu.inverse();
  for (std::size_t i = 0; i < cal.keys.size(); ++i)
    cal.uncertainty[i] =
        cal.values[i] * std::sqrt(std::max(0.0, cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i))));
}

// A point the fit has accepted: its values, misfit (the squared standardised residual), runs and
// its line in the path.
struct KeptPoint {
  std::vector<double> values;
  double misfit = 0;
  std::vector<Specimen> sims;
  std::size_t line = 0;
};

// A step is kept when it raises the misfit by at most this: the targets are standardised, so runs
// of nearly one model differ by about one unit in each. A step that raises it further left the
// region where the Jacobian holds (a beam that starts to crush at its rollers, say).
double misfit_allowance(const Eigen::VectorXd& z) { return static_cast<double>(z.size()); }

// Halfway back (in log) from a rejected point to the kept one; returns the largest step left.
double halve_towards(BaseCalibration& cal, const std::vector<double>& kept) {
  double largest = 0;
  for (std::size_t i = 0; i < cal.values.size(); ++i) {
    cal.values[i] = std::sqrt(cal.values[i] * kept[i]);
    largest = std::max(largest, std::abs(std::log(cal.values[i] / kept[i])));
  }
  return largest;
}

}  // namespace

BaseCalibration ContrastStudy::calibrate_base(const std::vector<std::string>& keys, int iterations, std::ostream& log) {
  BaseCalibration cal;
  cal.keys = keys;
  for (const auto& k : keys) {
    cal.start.push_back(simulator_.parameter(base_, k));
    cal.range.push_back(simulator_.parameter_range(k));
  }
  cal.values = cal.start;
  cal.uncertainty.assign(keys.size(), 0.0);
  cal.at_range_bound.assign(keys.size(), false);
  cal.form_targets = keys.size() > 2;
  const BaseTargets t = base_targets(sets_, groups_, scatter_, scale_rate_, cal.form_targets);
  std::optional<KeptPoint> kept;
  Eigen::MatrixXd last_jacobian;
  for (int it = 0; it <= iterations; ++it) {
    const ModelPlan here = point_model(base_, cal, scale_rate_);
    simulator_.check_inputs(here, t.reference, *t.metadata);
    std::vector<Specimen> sims = std::move(simulator_.simulate({here}, log).front());
    Comparison comparison;
    std::optional<Eigen::VectorXd> residual;
    try {
      residual = base_residual(t, sims, nullptr, comparison);
    } catch (const CurveWithoutRise& e) {
      const std::string why = simulated_without_rise(e, scale_rate_);
      if (!kept) throw std::runtime_error(fmt::format("the base model at {}: {}", point_values(cal), why));
      cal.path.push_back(fmt::format("{}: {} (step halved)", point_values(cal), why));
    }
    if (residual) cal.path.push_back(path_line(cal, *residual, t));
    // A point without a rise, or one whose misfit grew beyond noise, left the region the
    // Jacobian described: halfway back towards the kept point.
    if (kept && (!residual || residual->squaredNorm() > kept->misfit + misfit_allowance(*residual))) {
      if (residual)
        cal.path.back() += fmt::format(" (misfit {:.3g} against line {}'s {:.3g}: step halved)", residual->squaredNorm(),
                                       kept->line + 1, kept->misfit);
      log << "contrast: base " << cal.path.back() << '\n';
      if (halve_towards(cal, kept->values) < kConvergedStep) break;
      continue;
    }
    const Eigen::VectorXd& z = *residual;
    log << "contrast: base " << cal.path.back() << '\n';
    kept = KeptPoint{cal.values, z.squaredNorm(), std::move(sims), cal.path.size() - 1};
    if (it == iterations) break;
    std::vector<double> steps;
    const auto moved = simulator_.simulate(jacobian_models(base_, cal, scale_rate_, steps), log);
    try {
      last_jacobian = jacobian(t, moved, comparison, z, steps);
    } catch (const CurveWithoutRise& e) {
      throw std::runtime_error(fmt::format("the base fit's run 5 % from {}: {}", point_values(cal),
                                           simulated_without_rise(e, scale_rate_)));
    }
    // Converged: one more pass runs the stepped point, without a Jacobian.
    if (gauss_newton_step(cal, last_jacobian, z) < kConvergedStep) iterations = it + 1;
  }
  cal.values = kept->values;
  cal.returned_line = kept->line;
  set_uncertainties(cal, last_jacobian);
  base_ = with_parameters(base_, keys, cal.values);
  cal.form_error = compare(t.reference, *t.metadata, kept->sims);
  return cal;
}

}  // namespace shard::measure
