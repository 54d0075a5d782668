#include "shard/measure/contrast_diagnosis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <stdexcept>


namespace shard::measure {
namespace {

// Does resolution explain the form error? The same base fit at a packing of finer diameters.
BaseCalibration finer_calibration(const ContrastSets& sets, Simulator& simulator, const ModelPlan& base,
                                  const ContrastDiagnosisOptions& options, std::ostream& log) {
  ContrastStudy fine_study(sets, simulator, with_diameters_scaled(simulator, base, options.finer));
  log << fmt::format("diagnose: the base fit again with diameters x {:g}\n", options.finer);
  return fine_study.calibrate_base(options.params, options.params.empty() ? 0 : options.base_iterations, log);
}

// Each set's contrast against the effects' trials at their plausible sizes: the linear decision.
SetDiagnosis linear_diagnosis(const ContrastStudy& study, std::size_t set, const std::vector<CandidateEffect>& effects,
                              const std::vector<ContrastStudy::Simulated>& trials, const ContrastOptions& decide) {
  SetDiagnosis d;
  d.set = set;
  d.contrast = study.contrast(set, trials[0]);
  std::vector<EffectSignature> signatures;
  for (std::size_t e = 0; e < effects.size(); ++e)
    signatures.push_back({effects[e].name, effects[e].plausible - effects[e].neutral,
                          study.model_contrast(d.contrast, trials[1 + e], trials[0]), effects[e].scale_min(),
                          effects[e].scale_max(), effects[e].identifiable_at(study.rate_count(d.contrast))});
  d.linear = decide_contrast(d.contrast.difference, d.contrast.weight, signatures, study.dof(), decide);
  d.decision = d.linear;
  d.before = study.curve_contrast(d.contrast, trials[0], trials[0]);
  return d;
}

double share_of(const SetDiagnosis& d, const ContrastOptions& options) {
  const double t2 = d.decision.chi_square;
  if (!(t2 > 0)) return 0;
  if (d.pair && (pair_is_named(*d.pair, d.seconds_tried, options) || d.decision.verdict == kUnexplainedDifference))
    return std::max(0.0, (t2 - d.pair->chi_square) / t2);
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

bool names_a_pair(const SetDiagnosis& d, const ContrastOptions& options) {
  return d.pair && pair_is_named(*d.pair, d.seconds_tried, options) && d.withheld.empty();
}

void require_curve_agreement(std::vector<SetDiagnosis>& sets, const ContrastOptions& options) {
  for (auto& d : sets) {
    d.share = share_of(d, options);
    const std::string& verdict = d.decision.verdict;
    if (verdict == kNoDifference || verdict == kUnexplainedDifference) continue;
    const bool curve_agrees = d.after.rising_nrmse <= options.curve_floor_factor * d.after.rising_floor;
    if (curve_agrees && d.share >= options.min_share) continue;
    d.withheld = verdict;
    d.decision.verdict = kUnexplainedDifference;
    d.decision.rivals.clear();
  }
}

ContrastDiagnosis diagnose_contrasts(const ContrastSets& sets, Simulator& simulator, const ModelPlan& base,
                                     const std::vector<CandidateEffect>& library,
                                     const ContrastDiagnosisOptions& options, std::ostream& log) {
  ContrastDiagnosis out;
  ContrastStudy study(sets, simulator, base_at_grain_size(sets, simulator, base, options.lab_grain_size, log));
  out.calibration = study.calibrate_base(options.params, options.params.empty() ? 0 : options.base_iterations, log);
  if (options.finer > 0) {
    out.finer = finer_calibration(sets, simulator, base, options, log);
    out.finer_factor = options.finer;
  }
  out.effects = scaled_to_base_run(library, study, out.scaled_sizes, log);
  std::vector<ModelPlan> models{study.base()};
  for (const auto& e : out.effects) {
    models.push_back(with_effect(study.base(), e, e.plausible));
    models.back().probe = true;
  }
  out.rates = study.rates();
  log << fmt::format("diagnose: base and {} effects at {} rate(s)\n", out.effects.size(), out.rates.size());
  const auto trials = study.simulate(models, log);
  for (std::size_t s = 0; s < sets.sets.size(); ++s)
    if (!sets.reference || *sets.reference != s)
      out.sets.push_back(linear_diagnosis(study, s, out.effects, trials, options.decide));
  confirm_contrasts(study, out.effects, trials[0], out.sets, options.confirm, options.confirm_iterations,
                    options.decide, log);
  if (options.pairs > 0)
    confirm_contrast_pairs(study, out.effects, trials, out.sets, options.pairs, options.pair_iterations,
                           options.decide, log);
  require_curve_agreement(out.sets, options.decide);
  out.dof = study.dof();
  out.health = simulator.health();
  return out;
}

}  // namespace shard::measure
