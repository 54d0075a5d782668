#include "shard/measure/contrast_diagnosis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>

#include "shard/measure/reference_state.hpp"

namespace shard::measure {
namespace {

// Does resolution explain the form error? The same base fit at a packing of finer diameters.
BaseCalibration finer_calibration(const ContrastSets& sets, Simulator& simulator, const ModelPlan& base,
                                  const ContrastDiagnosisOptions& options, std::ostream& log) {
  ContrastStudy fine_study(sets, simulator, with_diameters_scaled(simulator, base, options.finer));
  log << fmt::format("diagnose: the base fit again with diameters x {:g}\n", options.finer);
  return fine_study.calibrate_base(options.params, options.params.empty() ? 0 : options.base_iterations, log);
}

// An effect whose physics lets it move the model both ways from the reference (more or less roller
// friction than the reference's, none included) gets a second trial one step the other way: an
// effect's response is seldom symmetric (no friction and twice the friction are no mirror images),
// so the trial on one side, extrapolated to the other, points the fit the wrong way.
bool moves_both_ways(const CandidateEffect& e) { return e.scale_min() <= -1 && e.scale_max() >= 1; }

// The trial runs of the study's first batch: the base, each effect at its plausible size, then the
// two-sided effects one step the other way (`mirror[e]`: the index of e's, or 0 when none).
struct Trials {
  std::vector<ModelPlan> models;
  std::vector<std::size_t> mirror;
};

Trials trial_models(const ModelPlan& base, const std::vector<CandidateEffect>& effects) {
  Trials t;
  t.models.push_back(base);
  for (const auto& e : effects) {
    t.models.push_back(with_effect(base, e, e.plausible));
    t.models.back().probe = true;
  }
  for (const auto& e : effects) {
    t.mirror.push_back(moves_both_ways(e) ? t.models.size() : 0);
    if (!moves_both_ways(e)) continue;
    t.models.push_back(with_effect(base, e, e.value_at(-1)));
    t.models.back().probe = true;
  }
  return t;
}

// The trials' runs, with the effects they sign. An effect whose trial on either side gives no
// usable run (a lubricated roller the beam slides on, a run inertia carries) is left out with its
// reason: its contrast cannot be read, and the library without it still judges the others (a set
// that needed it stays unexplained by the curve rule).
struct TrialRuns {
  std::vector<CandidateEffect> effects;
  std::vector<ContrastStudy::Simulated> runs;  // as Trials::models
  std::vector<std::size_t> mirror;
  std::vector<ContrastDiagnosis::LeftOutEffect> left_out;
};

std::string trial_label(const Trials& plan, const std::vector<CandidateEffect>& effects, std::size_t m) {
  for (std::size_t e = 0; e < effects.size(); ++e) {
    if (m == 1 + e) return fmt::format("the trial of {} at {:.4g}", effects[e].name, effects[e].plausible);
    if (plan.mirror[e] != 0 && m == plan.mirror[e]) return fmt::format("the trial of {} at {:.4g}", effects[e].name, effects[e].value_at(-1));
  }
  throw std::logic_error(fmt::format("trial_label: model {} is no effect's trial", m));
}

TrialRuns run_trials(ContrastStudy& study, const std::vector<CandidateEffect>& effects, std::ostream& log) {
  const Trials plan = trial_models(study.base(), effects);
  log << fmt::format("diagnose: base and {} effects ({} of them both ways) at {} rate(s)\n", effects.size(),
                     plan.models.size() - 1 - effects.size(), study.rates().size());
  TrialRuns out;
  out.runs.push_back(simulate_base(study, log));
  const std::vector<ModelPlan> trials(plan.models.begin() + 1, plan.models.end());
  std::vector<std::string> failures;
  auto runs = simulate_each(
      study, trials, [&](std::size_t m) { return trial_label(plan, effects, 1 + m); }, log, "diagnose", &failures);
  auto run_of = [&](std::size_t m) -> std::optional<ContrastStudy::Simulated>& { return runs[m - 1]; };
  auto failure_of = [&](std::size_t m) { return m == 0 ? std::string() : failures[m - 1]; };
  std::vector<std::size_t> kept;
  for (std::size_t e = 0; e < effects.size(); ++e) {
    std::size_t failed = 0;
    for (std::size_t m : {1 + e, plan.mirror[e]})
      if (failed == 0 && !failure_of(m).empty()) failed = m;
    if (failed == 0) kept.push_back(e);
    else out.left_out.push_back({effects[e].name, trial_label(plan, effects, failed) + ": " + failure_of(failed)});
  }
  for (std::size_t e : kept) {
    out.effects.push_back(effects[e]);
    out.runs.push_back(std::move(*run_of(1 + e)));
  }
  for (std::size_t e : kept) {
    out.mirror.push_back(plan.mirror[e] == 0 ? 0 : out.runs.size());
    if (plan.mirror[e] != 0) out.runs.push_back(std::move(*run_of(plan.mirror[e])));
  }
  return out;
}

// Effect e's contrast per trial step, on the side of neutral where the set's difference lies: the
// side whose fit alone leaves the smaller chi^2 (one-sided effects have one).
EffectSignature signature_for(const ContrastStudy& study, const SetDiagnosis& d, const CandidateEffect& e,
                              const std::vector<ContrastStudy::Simulated>& runs, std::size_t plus,
                              std::size_t mirror) {
  const bool nameable = e.identifiable_at(d.contrast.coverage);
  const double step = e.plausible - e.neutral;
  const auto t_plus = study.model_contrast(d.contrast, runs[plus], runs[0]);
  if (mirror == 0) return {e.name, step, t_plus, e.scale_min(), e.scale_max(), nameable};
  std::vector<double> t_minus = study.model_contrast(d.contrast, runs[mirror], runs[0]);
  for (double& x : t_minus) x = -x;  // per step towards plausible, read on the other side
  const EffectSignature up{e.name, step, t_plus, 0, e.scale_max(), nameable};
  const EffectSignature down{e.name, step, t_minus, e.scale_min(), 0, nameable};
  auto chi_square = [&](const EffectSignature& s) {
    return decide_contrast(d.contrast.difference, d.contrast.weight, {s}, study.noise()).fits.front().chi_square;
  };
  return chi_square(down) < chi_square(up) ? down : up;
}

// Each set's contrast against the effects' trials at their plausible sizes: the linear decision.
SetDiagnosis linear_diagnosis(const ContrastStudy& study, std::size_t set, const std::vector<CandidateEffect>& effects,
                              const std::vector<ContrastStudy::Simulated>& trials, const std::vector<std::size_t>& mirror,
                              const ContrastOptions& decide) {
  SetDiagnosis d;
  d.set = set;
  d.contrast = study.contrast(set, trials[0]);
  std::vector<EffectSignature> signatures;
  for (std::size_t e = 0; e < effects.size(); ++e)
    signatures.push_back(signature_for(study, d, effects[e], trials, 1 + e, mirror[e]));
  d.linear = decide_contrast(d.contrast.difference, d.contrast.weight, signatures, study.noise(), decide);
  d.decision = d.linear;
  d.before = study.curve_contrast(d.contrast, trials[0], trials[0]);
  return d;
}

double share_of(const SetDiagnosis& d, const ContrastOptions& options) {
  const double t2 = d.decision.chi_square;
  if (!(t2 > 0)) return 0;
  // A pair not named is the report's own line (pair_text); the share is that of what the verdict shows.
  if (d.pair && pair_is_named(*d.pair, d.seconds_tried, options)) return std::max(0.0, (t2 - d.pair->chi_square) / t2);
  return d.decision.fits.empty() ? 0 : std::max(0.0, d.decision.fits.front().drop / t2);
}

}  // namespace

ModelPlan base_at_grain_size(const ContrastSets& sets, const Simulator& simulator, const ModelPlan& base,
                             bool lab_grain_size, std::ostream& log) {
  if (!lab_grain_size) return base;
  const MeasurementSet& reference = sets.sets[sets.reference.value_or(0)];
  const double grain = reference.metadata.test.grain_size;
  if (!(grain > 0))
    throw std::runtime_error(fmt::format(
        "{}/metadata.toml: no [test] grain_size, but the model is asked to run at the lab's grain size. Fix: add "
        "grain_size = <mean grain diameter in m> under [test], or leave out --lab-grain-size",
        reference.folder.string()));
  return at_grain_size(simulator, base, grain, log);
}

double naming_floor(const ContrastStudy::CurveContrast& c, const ContrastOptions& options) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < c.xi.size(); ++i)
    if (c.rising[i]) {
      sum += std::pow(c.u_measured[i], 2) + std::pow(c.u_simulated[i], 2) +
             std::pow(options.form_tolerance * c.simulated[i], 2);
      ++n;
    }
  return n == 0 ? 0.0 : std::sqrt(sum / static_cast<double>(n));
}

bool curve_agrees(const ContrastStudy::CurveContrast& c, const ContrastOptions& options) {
  return c.rising_nrmse <= options.curve_floor_factor * naming_floor(c, options);
}

bool improves_on_base(const SetDiagnosis& d) { return d.after.nrmse < d.before.nrmse; }

bool curve_bears_out(const ContrastStudy::CurveContrast& after, const ContrastStudy::CurveContrast& before,
                     const ContrastOptions& options) {
  return curve_agrees(after, options) && after.nrmse < before.nrmse;
}

std::vector<double> component_uncertainties(const ContrastStudy::Contrast& c) {
  const std::vector<std::vector<double>> covariance = spd_inverse(c.weight);
  std::vector<double> u(covariance.size());
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = std::sqrt(covariance[i][i]);
  return u;
}

bool is_peak_force_component(const std::string& name) { return name.rfind("ln_peak_force", 0) == 0; }

bool is_rising_branch_component(const std::string& name) {
  return name.rfind("ln_stiffness", 0) == 0 || name.rfind("nonlinearity", 0) == 0;
}

double curve_name_sigmas(const std::string& component, const ContrastOptions& options) {
  if (is_peak_force_component(component)) return options.curve_name_peak_sigmas;
  if (is_rising_branch_component(component)) return options.curve_name_rising_sigmas;
  return std::numeric_limits<double>::infinity();
}

std::optional<std::size_t> component_missed_by_curve_name(const ContrastStudy::Contrast& c,
                                                          const std::vector<double>& model,
                                                          const ContrastOptions& options) {
  const std::vector<double> u = component_uncertainties(c);
  for (std::size_t i = 0; i < c.names.size() && i < model.size(); ++i) {
    const double widened = std::hypot(u[i], options.form_tolerance * model[i]);
    if (std::abs(model[i] - c.difference[i]) > curve_name_sigmas(c.names[i], options) * widened) return i;
  }
  return std::nullopt;
}

namespace {

// The curve rule on the set's shown model.
bool curve_bears_out(const SetDiagnosis& d, const ContrastOptions& options) {
  return curve_bears_out(d.after, d.before, options);
}

}  // namespace

bool names_a_pair(const SetDiagnosis& d, const ContrastOptions& options) {
  return d.pair && pair_is_named(*d.pair, d.seconds_tried, options) && d.withheld.empty();
}

namespace {

bool gives_a_name(const SetDiagnosis& d) {
  return d.decision.verdict != kNoDifference && d.decision.verdict != kUnexplainedDifference;
}

// The set reads "unexplained difference"; its name is kept as the closest, with the rule that withheld it.
void withhold(SetDiagnosis& d, WithheldBy by) {
  d.withheld = d.decision.verdict;
  d.withheld_by = by;
  d.decision.verdict = kUnexplainedDifference;
  d.decision.rivals.clear();
  d.named_by_curve = false;
}

}  // namespace

void require_curve_agreement(std::vector<SetDiagnosis>& sets, const ContrastOptions& options) {
  for (auto& d : sets) {
    d.share = share_of(d, options);
    if (gives_a_name(d) && !(curve_bears_out(d, options) && d.share >= options.min_share)) withhold(d, WithheldBy::curve);
  }
}

void name_by_curve(std::vector<SetDiagnosis>& sets, std::size_t tried, const ContrastOptions& options) {
  const double level = options.drop_p / static_cast<double>(std::max<std::size_t>(1, tried));
  for (auto& d : sets) {
    ContrastDecision& c = d.decision;
    if (c.verdict != kUnexplainedDifference || names_a_pair(d, options) || c.fits.empty()) continue;
    const ContrastFit& closest = c.fits.front();
    const double share = c.chi_square > 0 ? closest.drop / c.chi_square : 0.0;
    const bool curve_of_closest_agrees = d.after_effect == closest.name && curve_bears_out(d, options) &&
                                         !component_missed_by_curve_name(d.contrast, d.after_components, options);
    if (!(closest.scale != 0 && closest.identifiable && closest.p_drop < level && share >= options.curve_name_share &&
          curve_of_closest_agrees))
      continue;
    c.verdict = closest.name;
    c.rivals = rivals_of(c.fits, closest, level, options);
    d.withheld.clear();
    d.share = share;
    d.named_by_curve = true;
  }
}

void name_sets(std::vector<SetDiagnosis>& sets, std::size_t tried, const ContrastOptions& options,
               const std::function<void(std::vector<SetDiagnosis>&)>& seek_pairs) {
  require_curve_agreement(sets, options);
  name_by_curve(sets, tried, options);
  if (!seek_pairs) return;
  seek_pairs(sets);
  require_curve_agreement(sets, options);
}

void withhold_names_of_own_scatter(std::vector<SetDiagnosis>& sets, const ContrastStudy& study) {
  const auto carries_own_scatter = [&](std::size_t set) {
    for (std::size_t gi = 0; gi < study.groups().size(); ++gi)
      if (study.groups()[gi].set == set && study.scatter().own[gi]) return true;
    return false;
  };
  for (auto& d : sets)
    if (gives_a_name(d) && carries_own_scatter(d.set)) withhold(d, WithheldBy::own_scatter);
}

void withhold_names_of_invalid_fractures(std::vector<SetDiagnosis>& sets, const ContrastSets& measured) {
  for (auto& d : sets) {
    d.fractures = fracture_validity(measured.sets[d.set]);
    if (gives_a_name(d) && d.fractures.set_invalid()) withhold(d, WithheldBy::fractures);
  }
}

void withhold_names_on_a_distant_base(std::vector<SetDiagnosis>& sets, double base_nrmse,
                                      const ContrastOptions& options) {
  if (!(base_nrmse > options.base_nrmse_limit)) return;
  for (auto& d : sets)
    if (gives_a_name(d)) withhold(d, WithheldBy::base);
}

ContrastDiagnosis diagnose_contrasts(const ContrastSets& sets, Simulator& simulator, const ModelPlan& base,
                                     const std::vector<CandidateEffect>& library,
                                     const ContrastDiagnosisOptions& options, std::ostream& log) {
  ContrastDiagnosis out;
  check_effects_reach(library, base);
  check_assumptions_apply(simulator, base, options.assumptions);
  ContrastStudy study(sets, simulator, base_at_grain_size(sets, simulator, base, options.lab_grain_size, log),
                      options.decide.own_scatter_p);
  out.calibration = study.calibrate_base(options.params, options.params.empty() ? 0 : options.base_iterations, log);
  if (options.finer > 0) {
    out.finer = finer_calibration(sets, simulator, base, options, log);
    out.finer_factor = options.finer;
  }
  TrialRuns tried = run_trials(
      study, centred_on_reference(scaled_to_base_run(library, study, out.scaled_sizes, log), study.base(), log), log);
  out.effects = std::move(tried.effects);
  out.left_out = std::move(tried.left_out);
  out.rates = study.rates();
  const auto& trials = tried.runs;
  for (std::size_t s = 0; s < sets.sets.size(); ++s)
    if (!sets.reference || *sets.reference != s)
      out.sets.push_back(linear_diagnosis(study, s, out.effects, trials, tried.mirror, options.decide));
  confirm_contrasts(study, out.effects, trials[0], out.sets, options.confirm, options.confirm_iterations,
                    options.confirm_probes, options.decide, log);
  std::function<void(std::vector<SetDiagnosis>&)> seek_pairs;
  if (options.pairs > 0)
    seek_pairs = [&](std::vector<SetDiagnosis>& sets_now) {
      confirm_contrast_pairs(study, out.effects, trials, tried.mirror, sets_now, options.pairs,
                             options.pair_iterations, options.decide, log);
    };
  name_sets(out.sets, out.effects.size(), options.decide, seek_pairs);
  require_resolved_rate_dependence(out.sets, study, trials[0], out.effects, options.decide);
  withhold_names_of_own_scatter(out.sets, study);
  withhold_names_of_invalid_fractures(out.sets, sets);
  withhold_names_on_a_distant_base(out.sets, out.calibration.form_error.nrmse, options.decide);
  if (sets.reference) out.reference_fractures = fracture_validity(sets.sets[*sets.reference]);
  if (!options.assumptions.empty())
    assess_assumptions(study, out.effects, out.sets, options.assumptions, options.decide, log);
  out.dof = study.noise().dof;
  for (std::size_t gi = 0; gi < study.groups().size(); ++gi)
    out.scatter.push_back({study.groups()[gi].set, study.groups()[gi].rate, study.scatter().ratio[gi],
                           contrast_component_names()[study.scatter().component[gi]], study.scatter().p_value[gi],
                           study.scatter().own[gi]});
  out.health = simulator.health();
  return out;
}

}  // namespace shard::measure
