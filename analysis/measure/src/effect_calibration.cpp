#include "shard/measure/effect_calibration.hpp"

#include <fmt/format.h>

#include <nlopt.hpp>

#include <algorithm>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string_view>

namespace shard::measure {

namespace {

// The fitted coordinate sits at its bound within this relative tolerance.
constexpr double kAtBound = 1e-6;

// The objective: one model per point x (base parameters relative to their start, then the
// effect in plausible sizes from neutral), simulated and scored against the base model's band.
class Objective {
 public:
  Objective(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene, const EffectCalibration& fit,
            Scoring scoring, std::ostream& log)
      : simulator_(simulator), data_(data), scene_(scene), fit_(fit), scoring_(scoring), log_(log) {}

  ModelPlan model(const std::vector<double>& x) const {
    std::vector<double> v;
    for (std::size_t i = 0; i < fit_.keys.size(); ++i) v.push_back(fit_.start[i] * x[i]);
    ModelPlan m = with_parameters(scene_, fit_.keys, v);
    if (fit_.effect) m = with_effect(m, *fit_.effect, fit_.effect->value_at(x.back()));
    return m;
  }
  RateComparison evaluate(const std::vector<double>& x) const {
    return simulate_and_compare(simulator_, data_, {model(x)}, log_).front();
  }
  double score(const RateComparison& c) const { return model_score(c, fit_.before, scoring_); }
  double operator()(const std::vector<double>& x) {
    const double chi2 = score(evaluate(x));
    ++evaluations_;
    log_ << fmt::format("calibrate-effect: evaluation {} chi^2 {:.2f}\n", evaluations_, chi2);
    if (chi2 < best_) best_ = chi2, best_x_ = x;
    return chi2;
  }
  int evaluations() const { return evaluations_; }
  const std::vector<double>& best_x() const { return best_x_; }

 private:
  Simulator& simulator_;
  const MeasuredRates& data_;
  const ModelPlan& scene_;
  const EffectCalibration& fit_;
  Scoring scoring_;
  std::ostream& log_;
  int evaluations_ = 0;
  double best_ = std::numeric_limits<double>::infinity();
  std::vector<double> best_x_;
};

double nlopt_objective(unsigned n, const double* x, double* grad, void* data) {
  (void)grad;  // derivative-free
  return (*static_cast<Objective*>(data))(std::vector<double>(x, x + n));
}

// The linearised start (diagnose_set's first step on the same runs, so its refit is cached) and
// the range searched: base parameters 0.5-2 x their start, the effect from neutral to four
// plausible sizes inside its physical range. Sets `fit.before`, the base model's comparison.
std::vector<double> linearised_start(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene,
                                     EffectCalibration& fit, Scoring scoring, std::ostream& log) {
  std::vector<const CandidateEffect*> candidates;
  if (fit.effect) candidates.push_back(&*fit.effect);
  const StepLinearisation lin =
      linearise_step(simulator, data, scene, fit.keys, StepModel{fit.start, {}}, candidates, nullptr, scoring, log);
  fit.before = lin.base_comparison;
  const LinearRefit lr = linear_refit(lin.base.values, lin.jacobian, lin.signatures);
  const std::size_t n = fit.keys.size() + (fit.effect ? 1 : 0);
  fit.lower.assign(n, 0.5), fit.upper.assign(n, 2.0);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < fit.keys.size(); ++i) x[i] = clamp_base_factor(1 + lr.base_step[i]);
  if (fit.effect) {
    fit.lower.back() = std::max(-4.0, fit.effect->scale_min());
    fit.upper.back() = std::min(4.0, fit.effect->scale_max());
    x.back() = std::clamp(clamp_effect_scale(*fit.effect, lr.effect_scale.front()), fit.lower.back(), fit.upper.back());
  }
  return x;
}

// BOBYQA from `x`; fills fit.best, fit.stop and fit.evaluations.
void optimise(Objective& objective, EffectCalibration& fit, std::vector<double> x, int max_evaluations) {
  const auto n = static_cast<unsigned>(x.size());
  nlopt::opt opt(nlopt::LN_BOBYQA, n);
  opt.set_lower_bounds(fit.lower);
  opt.set_upper_bounds(fit.upper);
  opt.set_min_objective(nlopt_objective, &objective);
  opt.set_maxeval(max_evaluations);
  opt.set_xtol_rel(1e-3);
  std::vector<double> step(n, 0.05);
  if (fit.effect) step.back() = 0.25;
  opt.set_initial_step(step);
  double minimum = 0;
  fit.stop = "converged";
  try {
    if (opt.optimize(x, minimum) == nlopt::MAXEVAL_REACHED) fit.stop = "evaluation budget reached";
  } catch (const nlopt::roundoff_limited&) {
    fit.stop = "round-off limited";
  } catch (const std::runtime_error& e) {
    // NLopt's generic NLOPT_FAILURE: BOBYQA's quadratic model can break down on an objective
    // with packing noise. Every evaluation so far is a finished simulation; keep the best one
    // rather than lose them. Anything else (a failed run) still ends the calibration.
    if (std::string_view(e.what()) != "nlopt failure" || objective.best_x().empty()) throw;
    fit.stop = "BOBYQA stopped (its quadratic model broke down on the noisy objective); the best evaluation is kept";
  }
  fit.best = objective.best_x().empty() ? x : objective.best_x();
  fit.evaluations = objective.evaluations();
}

// The fitted model's comparison, and the credit: the fitted base parameters with the effect
// switched off (one more run per seed).
void score_fit(const Objective& objective, EffectCalibration& fit) {
  fit.after = objective.evaluate(fit.best);
  fit.chi_square_before = objective.score(fit.before);
  fit.chi_square_after = objective.score(fit.after);
  if (!fit.effect) return;
  std::vector<double> off = fit.best;
  off.back() = 0;  // value_at(0): neutral
  fit.base_only = objective.evaluate(off);
  fit.chi_square_base_only = objective.score(*fit.base_only);
  fit.credit = credit_gain(fit.chi_square_before, *fit.chi_square_base_only, fit.chi_square_after);
}

}  // namespace

RangeEnd EffectCalibration::base_at_bound(std::size_t i) const {
  if (best[i] <= lower[i] * (1 + kAtBound)) return RangeEnd::Lower;
  if (best[i] >= upper[i] * (1 - kAtBound)) return RangeEnd::Upper;
  return RangeEnd::None;
}

RangeEnd EffectCalibration::effect_at_bound() const {
  if (!effect) return RangeEnd::None;
  if (best.back() <= lower.back() + kAtBound) return RangeEnd::Lower;
  if (best.back() >= upper.back() - kAtBound) return RangeEnd::Upper;
  return RangeEnd::None;
}

EffectCalibration calibrate_effect(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene,
                                   std::optional<CandidateEffect> effect, const EffectCalibrationOptions& options,
                                   std::ostream& log) {
  if (options.params.empty() && !effect)
    throw std::invalid_argument("calibrate-effect: give --with EFFECT and/or --param");
  EffectCalibration fit;
  fit.keys = options.params;
  for (const auto& k : fit.keys) fit.start.push_back(simulator.parameter(scene, k));
  // The trial size as diagnose_set resolves it (the base run at the scene's values), so the
  // linearised start is diagnose's first step.
  std::vector<CandidateEffect> effects;
  if (effect) effects.push_back(std::move(*effect));
  std::string scaled;
  effects = plausible_on_base_run(std::move(effects), simulator, data, step_plan(scene, fit.keys, {fit.start, {}}),
                                  scaled, log);
  if (!effects.empty()) fit.effect = effects.front();
  Objective objective(simulator, data, scene, fit, options.scoring, log);
  optimise(objective, fit, linearised_start(simulator, data, scene, fit, options.scoring, log),
           options.max_evaluations);
  score_fit(objective, fit);
  fit.health = simulator.health();
  return fit;
}

}  // namespace shard::measure
