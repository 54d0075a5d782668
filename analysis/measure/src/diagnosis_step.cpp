#include "shard/measure/diagnosis_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "shard/measure/effect_scaling.hpp"

namespace shard::measure {
namespace {

constexpr double kParameterStep = 0.05;  // relative step of the base parameters (as linearise)
constexpr double kKeptStep = 0.25;       // step of a kept effect, in trial sizes

std::vector<double> difference(const ResidualVector& r, const ResidualVector& base, const std::string& what,
                               double scale) {
  if (r.names != base.names)
    throw std::runtime_error(fmt::format("{} changed which residual components exist (a regime or feature vanished); "
                                         "use a smaller size",
                                         what));
  std::vector<double> d(r.values.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = (r.values[i] - base.values[i]) / scale;
  return d;
}

// Each packing seed's change from the base run to `run` alone, in the units of each run's own
// (scored) band, as the ensemble's signature is; empty with one seed or when a seed lacks a
// component the ensemble has. `base_seeds`: the base run's seed_residual_vectors in its band.
std::vector<std::vector<double>> seed_differences(const RateComparison& run, const std::vector<ResidualVector>& base_seeds,
                                                  const std::vector<std::string>& names) {
  std::vector<std::vector<double>> out;
  const std::vector<ResidualVector> run_seeds = run.seed_residual_vectors(run);
  for (std::size_t seed = 0; seed < run_seeds.size() && seed < base_seeds.size(); ++seed) {
    const ResidualVector &with = run_seeds[seed], &without = base_seeds[seed];
    if (with.names != names || without.names != names) return {};
    auto& d = out.emplace_back(names.size());
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = with.values[i] - without.values[i];
  }
  return out;
}

}  // namespace

std::string model_name(const StepModel& m) {
  std::string s = "base";
  for (const auto& [e, v] : m.kept) s += fmt::format(" + {} ({})", e->name, e->sized(v));
  return s;
}

ModelPlan step_plan(const ModelPlan& scene, const std::vector<std::string>& keys, const StepModel& model) {
  return with_effects(with_parameters(scene, keys, model.parameters), model.kept);
}

double effect_scale(const CandidateEffect& e, double value) { return (value - e.neutral) / (e.plausible - e.neutral); }

Scoring scoring_from_name(const std::string& name) {
  if (name == "own") return Scoring::Own;
  if (name == "frozen") return Scoring::FrozenBand;
  if (name == "likelihood") return Scoring::Likelihood;
  throw std::runtime_error(fmt::format("--scoring {}: use 'own' (each model's own band), 'frozen' (the base model's band for "
                                       "every model) or 'likelihood' (own band plus the log-variance term)",
                                       name));
}

double model_score(const RateComparison& c, const RateComparison& reference, Scoring scoring) {
  if (scoring == Scoring::Own) return c.chi_square();
  if (scoring == Scoring::FrozenBand) return with_band(c, reference).chi_square();
  double log_det = 0;
  for (std::size_t k = 0; k < c.at.size() && k < reference.at.size(); ++k)
    log_det += log_variance_ratio(c.at[k], reference.at[k]);
  return c.chi_square() + log_det;
}

double failure_point_chi_square(const RateComparison& c) {
  double sum = 0;
  for (const auto& at : c.at) {
    bool found = false;
    for (const auto& f : at.features)
      if (f.feature == Feature::FailureDisplacement && std::isfinite(f.score)) {
        found = true;
        if (!f.judged) sum += f.score * f.score;
      }
    if (!found) return std::numeric_limits<double>::quiet_NaN();
  }
  return sum;
}

RateComparison with_band(const RateComparison& c, const RateComparison& reference) {
  RateComparison out = c;
  for (std::size_t k = 0; k < out.at.size(); ++k) out.at[k] = with_simulated_band(c.at[k], reference.at[k]);
  return out;
}

StepLinearisation linearise_step(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene,
                                 const std::vector<std::string>& keys, const StepModel& model,
                                 const std::vector<const CandidateEffect*>& candidates, const RateComparison* band,
                                 Scoring scoring, std::ostream& log) {
  StepLinearisation l;
  std::vector<ModelPlan> models{step_plan(scene, keys, model)};
  for (std::size_t i = 0; i < keys.size(); ++i) {
    StepModel stepped = model;
    stepped.parameters[i] *= 1 + kParameterStep;
    models.push_back(step_plan(scene, keys, stepped));
  }
  for (std::size_t j = 0; j < model.kept.size(); ++j) {
    const auto& [effect, value] = model.kept[j];
    const double scale = effect_scale(*effect, value);
    // Upwards unless that leaves the physical range (value_at would clamp to the same value).
    const double up = effect->value_at(scale + kKeptStep);
    const double step = std::abs(effect_scale(*effect, up) - scale) > 0.5 * kKeptStep ? kKeptStep : -kKeptStep;
    StepModel stepped = model;
    stepped.kept[j].second = effect->value_at(scale + step);
    l.kept_scale_step.push_back(effect_scale(*effect, stepped.kept[j].second) - scale);
    models.push_back(step_plan(scene, keys, stepped));
  }
  for (const auto* e : candidates) models.push_back(with_effect(models.front(), *e, e->plausible));
  auto comparisons = simulate_and_compare(simulator, data, models, log);
  l.base_comparison = comparisons[0];
  const RateComparison& reference = band ? *band : comparisons[0];
  if (scoring == Scoring::FrozenBand)
    for (auto& c : comparisons) c = with_band(c, reference);
  l.base = comparisons[0].residual_vector();
  std::size_t m = 1;
  for (std::size_t i = 0; i < keys.size(); ++i, ++m)
    l.jacobian.push_back(difference(comparisons[m].residual_vector(), l.base, keys[i], kParameterStep));
  for (std::size_t j = 0; j < model.kept.size(); ++j, ++m)
    l.jacobian.push_back(difference(comparisons[m].residual_vector(), l.base, model.kept[j].first->name,
                                    l.kept_scale_step[j]));
  const std::vector<ResidualVector> base_seeds = comparisons[0].seed_residual_vectors(comparisons[0]);
  for (const auto* e : candidates) {
    // The candidate switched on from its neutral value: one trial step.
    l.signatures.push_back({e->name, e->plausible - e->neutral,
                            difference(comparisons[m].residual_vector(), l.base, e->name, 1.0), e->scale_min(),
                            e->scale_max(), e->identifiable_at(data.coverage()),
                            seed_differences(comparisons[m], base_seeds, l.base.names)});
    ++m;
  }
  return l;
}

std::vector<CandidateEffect> plausible_on_base_run(std::vector<CandidateEffect> effects, Simulator& simulator,
                                                   const MeasuredRates& data, const ModelPlan& base,
                                                   std::string& described, std::ostream& log) {
  const RateGroups& measured = data.groups;
  described.clear();
  if (std::none_of(effects.begin(), effects.end(), [](const CandidateEffect& e) { return !e.plausible_from.empty(); }))
    return effects;
  std::vector<Specimen> every_rate;
  for (const auto& at : measured.specimens) every_rate.insert(every_rate.end(), at.begin(), at.end());
  simulator.check_inputs(base, every_rate, data.metadata);
  std::vector<ModelPlan> runs;
  for (double r : measured.rates) {
    ModelPlan at = base;
    at.loading_rate = r;
    runs.push_back(std::move(at));
  }
  std::vector<std::vector<Curve>> curves;
  for (const auto& replicates : simulator.simulate(runs, log)) {
    auto& at_rate = curves.emplace_back();
    for (const auto& sp : replicates) at_rate.push_back(sp.curve);
  }
  const TestScales scales = base_run_scales(curves);
  effects = with_test_plausible(std::move(effects), scales);
  described = describe_scaled_plausible(effects, scales);
  log << "diagnose: plausible sizes from the base run:\n" << described;
  return effects;
}

RefitPlan refit_plan(const std::vector<std::string>& keys, const StepModel& start, const LinearRefit& lr,
                     const CandidateEffect* added) {
  RefitPlan r;
  r.model = start;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const double asked = 1 + lr.base_step[i];
    const double factor = clamp_base_factor(asked);
    r.model.parameters[i] *= factor;
    if (factor != asked) {
      r.base_at_bound = true;
      r.at_bound.push_back(fmt::format("{} at {:.3g} x its start (asked {:.3g} x; the refit's range is 0.55-1.9 x)", keys[i],
                                       factor, asked));
    }
  }
  auto place = [&](const CandidateEffect& e, double asked_scale) {
    // The step of an effect is bounded like calibrate-effect's start, then by its physical range.
    const double scale = clamp_effect_scale(e, asked_scale);
    const double value = e.value_at(scale);
    const double asked_value = e.neutral + asked_scale * (e.plausible - e.neutral);
    if (std::abs(effect_scale(e, value) - asked_scale) > 1e-9 * std::max(1.0, std::abs(asked_scale)))
      r.at_bound.push_back(fmt::format(
          "{} at {} (asked {:.4g}; bound: {})", e.name, e.sized(value), asked_value,
          value == e.min || value == e.max
              ? "its physical range [min, max]"
              : "0.05-3.9 plausible sizes from neutral, on the trial's side unless its range reaches the other"));
    return value;
  };
  const std::size_t p = keys.size();
  for (std::size_t j = 0; j < start.kept.size(); ++j) {
    const auto& [effect, value] = start.kept[j];
    r.model.kept[j].second = place(*effect, effect_scale(*effect, value) + lr.base_step[p + j]);
  }
  if (added) r.model.kept.emplace_back(added, place(*added, lr.effect_scale.front()));
  return r;
}

std::vector<double> refit_step(const std::vector<std::string>& keys, const StepModel& start, const StepModel& refit,
                               const CandidateEffect* added) {
  std::vector<double> step;
  for (std::size_t i = 0; i < keys.size(); ++i) step.push_back(refit.parameters[i] / start.parameters[i] - 1);
  for (std::size_t j = 0; j < start.kept.size(); ++j) {
    const CandidateEffect& e = *start.kept[j].first;
    step.push_back(effect_scale(e, refit.kept[j].second) - effect_scale(e, start.kept[j].second));
  }
  if (added) step.push_back(effect_scale(*added, refit.kept.back().second));
  return step;
}

std::optional<LinearRefit> secant_refit(const ResidualVector& r0, const std::vector<std::vector<double>>& jacobian,
                                        const EffectSignature* added, const std::vector<double>& step,
                                        const ResidualVector& simulated) {
  if (simulated.names != r0.names) return std::nullopt;
  std::vector<std::vector<double>> columns = jacobian;
  if (added) columns.push_back(added->signature);
  if (columns.size() != step.size()) throw std::logic_error("secant_refit: the step does not match the linearisation");
  double norm2 = 0;
  for (double x : step) norm2 += x * x;
  if (!(norm2 > 1e-12)) return std::nullopt;
  const std::size_t m = r0.values.size();
  // What the linearisation missed at the refit: simulated - (r0 + B step).
  std::vector<double> miss(m);
  for (std::size_t i = 0; i < m; ++i) {
    double predicted = r0.values[i];
    for (std::size_t c = 0; c < columns.size(); ++c) predicted += columns[c][i] * step[c];
    miss[i] = simulated.values[i] - predicted;
  }
  for (std::size_t c = 0; c < columns.size(); ++c)
    for (std::size_t i = 0; i < m; ++i) columns[c][i] += miss[i] * step[c] / norm2;
  if (!added) return linear_refit(r0.values, columns, {});
  EffectSignature updated = *added;
  updated.signature = columns.back();
  columns.pop_back();
  return linear_refit(r0.values, columns, {updated});
}

}  // namespace shard::measure
