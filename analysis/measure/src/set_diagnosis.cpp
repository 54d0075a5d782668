#include "shard/measure/set_diagnosis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/measure/contrast.hpp"
#include "shard/measure/statistics.hpp"

namespace shard::measure {

namespace {

// One residual component of a vector by name; NaN when the vector lacks it.
double component(const ResidualVector& v, const std::string& name) {
  for (std::size_t i = 0; i < v.names.size(); ++i)
    if (v.names[i] == name) return v.values[i];
  return std::numeric_limits<double>::quiet_NaN();
}

// seed_consistency_p of an effect refit against the base refit, seed by seed: each seed's move of
// the residual (effect refit minus base refit, that seed alone) along the base refit's residual,
// over the components every seed has. 0 (not tested) with fewer than two seeds or a failed run.
double seed_resolution_p(const RefitRun& base, const RefitRun& effect) {
  const std::size_t seeds = std::min(base.seed_residuals.size(), effect.seed_residuals.size());
  if (seeds < 2 || !effect.failure.empty()) return 0;
  std::vector<double> along;
  std::vector<std::vector<double>> moves(seeds);
  for (std::size_t i = 0; i < base.residual.names.size(); ++i) {
    const std::string& name = base.residual.names[i];
    std::vector<double> move;
    for (std::size_t s = 0; s < seeds; ++s) move.push_back(component(effect.seed_residuals[s], name) - component(base.seed_residuals[s], name));
    if (!std::all_of(move.begin(), move.end(), [](double x) { return std::isfinite(x); })) continue;
    along.push_back(-base.residual.values[i]);  // the way that takes the residual towards zero
    for (std::size_t s = 0; s < seeds; ++s) moves[s].push_back(move[s]);
  }
  if (along.empty()) return 0;
  return seed_consistency_p(along, moves);
}

}  // namespace

const CandidateEffect* SetDiagnosisResult::effect(const std::string& name) const {
  for (const auto& e : effects)
    if (e.name == name) return &e;
  return nullptr;
}

namespace {

// The information criteria of each refit against the base refit that stands (refits[0]).
void compare_with_base_refit(std::vector<RefitRun>& refits, std::size_t components) {
  for (std::size_t k = 0; k < refits.size(); ++k) {
    RefitRun& c = refits[k];
    if (!c.failure.empty()) continue;
    const double extra = k == 0 ? 0 : 1;
    c.delta_aic = c.chi_square - refits.front().chi_square + 2 * extra;
    c.delta_bic = c.chi_square - refits.front().chi_square + extra * std::log(static_cast<double>(components));
  }
}

std::string first_line(const std::exception& e) {
  const std::string what = e.what();
  return what.substr(0, what.find('\n'));
}

const RefitRun& refit_named(const DiagnosisStepRecord& s, const std::string& name) {
  for (const auto& c : s.refits)
    if (c.name == name) return c;
  throw std::logic_error("diagnose: no refit of " + name);
}

// The stepwise diagnosis's state: what every step shares, and the path so far.
class StepwiseDiagnoser {
 public:
  StepwiseDiagnoser(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene,
                    const SetDiagnosisOptions& options, SetDiagnosisResult& out, std::ostream& log)
      : simulator_(simulator), data_(data), scene_(scene), options_(options), out_(out), log_(log) {}

  void run();

 private:
  enum class Next { Step, Stop };
  Next step(int index);
  std::vector<const CandidateEffect*> candidates() const;
  void plan_refits(DiagnosisStepRecord& s) const;
  RefitRun linear_refit_run(const DiagnosisStepRecord& s, const CandidateEffect* effect,
                            const EffectSignature* signature) const;
  std::vector<RateComparison> simulate_refits(std::vector<RefitRun>& refits);
  void run_refits(std::vector<RefitRun>& refits, std::size_t components);
  void iterate_refits(const DiagnosisStepRecord& s, std::vector<RefitRun>& refits);
  bool secant_round(const DiagnosisStepRecord& s, std::vector<RefitRun>& refits);
  void decide(DiagnosisStepRecord& s);
  Next follow_decision(DiagnosisStepRecord& s, bool last);
  void record(const DiagnosisStepRecord& s, const RefitRun& refit, bool named);

  Simulator& simulator_;
  const MeasuredRates& data_;
  const ModelPlan& scene_;
  const SetDiagnosisOptions& options_;
  SetDiagnosisResult& out_;
  std::ostream& log_;
  RateComparison band_;           // the base model's: every run of every step is scored against it
  std::size_t refits_tried_ = 0;  // nameable refits of the earlier steps (the path's Bonferroni share)
};

void StepwiseDiagnoser::run() {
  for (int index = 0; index < options_.max_effects; ++index)
    if (step(index) == Next::Stop) break;
  if (!out_.path.empty()) out_.verdict = stepwise_verdict(out_.path);
  else if (out_.verdict.empty()) out_.verdict = kUnexplained;
}

// The effects not kept yet that can be on beside every kept one (combinable: a kept effect's
// plugin switch can leave another effect's parameter without a plugin to take it).
std::vector<const CandidateEffect*> StepwiseDiagnoser::candidates() const {
  std::vector<const CandidateEffect*> out;
  for (const auto& e : out_.effects) {
    bool kept = false, fits_in = true;
    for (const auto& k : out_.model.kept) {
      kept = kept || k.first->name == e.name;
      fits_in = fits_in && combinable(*k.first, e);
    }
    if (!kept && fits_in) out.push_back(&e);
  }
  return out;
}

StepwiseDiagnoser::Next StepwiseDiagnoser::step(int index) {
  std::vector<const CandidateEffect*> candidates = this->candidates();
  if (candidates.empty()) return Next::Stop;
  DiagnosisStepRecord& s = out_.steps.emplace_back();  // not moved below: the references into it stay valid
  s.model = out_.model;
  s.candidates = std::move(candidates);
  log_ << fmt::format("diagnose step {}: {}, {} parameter steps and {} effects\n", index + 1, model_name(s.model),
                      out_.keys.size() + s.model.kept.size(), s.candidates.size());
  s.lin = linearise_step(simulator_, data_, scene_, out_.keys, s.model, s.candidates, index == 0 ? nullptr : &band_,
                         options_.scoring, log_);
  if (index == 0) band_ = s.lin.base_comparison;
  s.diagnosis = diagnose(s.lin.base.names, s.lin.base.values, s.lin.jacobian, s.lin.signatures);
  // Noise needs no refit (its runs would be wasted); without refits the score test decides.
  if (index == 0 && (s.diagnosis.verdict == kAdequate || options_.refit <= 0)) {
    out_.verdict = s.diagnosis.verdict;
    return Next::Stop;
  }
  plan_refits(s);
  run_refits(s.refits, s.lin.base.values.size());
  // Later steps' refits start from a kept effect whose size the step that kept it did not
  // identify: they are compared converged (docs/explanation/diagnosis.md "Several effects at
  // once"). Step 1's refits all start at the scene's base and stay one linear step.
  if (!s.model.kept.empty()) iterate_refits(s, s.refits);
  compare_with_base_refit(s.refits, s.lin.base.values.size());
  decide(s);
  return follow_decision(s, index + 1 == options_.max_effects);
}

RefitRun StepwiseDiagnoser::linear_refit_run(const DiagnosisStepRecord& s, const CandidateEffect* effect,
                                             const EffectSignature* signature) const {
  RefitRun c;
  c.name = effect ? effect->name : "base refit";
  std::vector<EffectSignature> added;
  if (signature) added.push_back(*signature);
  c.plan = refit_plan(out_.keys, s.model, linear_refit(s.lin.base.values, s.lin.jacobian, added), effect);
  c.effect = effect;
  c.signature = signature;
  if (effect) c.effect_value = c.plan.model.kept.back().second;
  return c;
}

// The base refit, then the top `refit` effects that can be named; an effect these data cannot
// identify (a rate effect at one rate) that ranks among them is refit in addition, to show how
// much it explains, without taking a nameable effect's place. Effects the packing seeds resolve
// (EffectScore::resolved) take the places first: an unresolved score may be the model's packing
// scatter, and only the refit's own seed test (ConfirmationRule::seed_p) tells.
void StepwiseDiagnoser::plan_refits(DiagnosisStepRecord& s) const {
  s.refits.push_back(linear_refit_run(s, nullptr, nullptr));
  std::vector<const EffectScore*> order;
  for (bool resolved : {true, false})
    for (const auto& r : s.diagnosis.ranking)
      if (r.resolved == resolved && r.score > 0) order.push_back(&r);
  const auto tops = static_cast<std::size_t>(std::max(0, options_.refit));
  std::size_t nameable = 0;
  for (std::size_t k = 0; k < order.size() && nameable < tops; ++k)
    for (std::size_t e = 0; e < s.candidates.size(); ++e)
      if (s.candidates[e]->name == order[k]->name) {
        s.refits.push_back(linear_refit_run(s, s.candidates[e], &s.lin.signatures[e]));
        if (s.lin.signatures[e].identifiable) ++nameable;
      }
}

// One batch; when a run fails (a linear step can reach an unstable size), the models are retried
// one by one: finished runs are cached, and a failed effect refit is reported and left out of the
// decision instead of ending the diagnosis.
std::vector<RateComparison> StepwiseDiagnoser::simulate_refits(std::vector<RefitRun>& refits) {
  std::vector<ModelPlan> models;
  for (const auto& c : refits) models.push_back(step_plan(scene_, out_.keys, c.plan.model));
  try {
    return simulate_and_compare(simulator_, data_, models, log_);
  } catch (const std::exception&) {
    std::vector<RateComparison> sims(models.size());
    for (std::size_t k = 0; k < models.size(); ++k) try {
        sims[k] = simulate_and_compare(simulator_, data_, {models[k]}, log_).front();
      } catch (const std::exception& e) {
        if (k == 0) throw;  // without the base refit there is nothing to compare with
        refits[k].failure = first_line(e);
      }
    return sims;
  }
}

void StepwiseDiagnoser::run_refits(std::vector<RefitRun>& refits, std::size_t components) {
  const std::vector<RateComparison> sims = simulate_refits(refits);
  const Scoring scoring = options_.scoring;
  for (std::size_t k = 0; k < refits.size(); ++k) {
    RefitRun& c = refits[k];
    if (!c.failure.empty()) {
      c.chi_square = c.nrmse = std::numeric_limits<double>::infinity();
      continue;
    }
    const RateComparison scored = scoring == Scoring::FrozenBand ? with_band(sims[k], band_) : sims[k];
    c.chi_square = model_score(sims[k], band_, scoring);
    c.nrmse = sims[k].nrmse();
    c.noise_nrmse = sims[k].noise_nrmse();
    c.residual = scored.residual_vector();
    c.seed_residuals = sims[k].seed_residual_vectors(scored);
    c.failure_chi_square = failure_point_chi_square(scored);
  }
  compare_with_base_refit(refits, components);
}

// Secant iterations of the effect refits refits[1..] (refits[0]: the step's base refit, the
// decision's reference, stays linear: iterated, it traded the features for the curve), up to
// refit_iterations times while some run improves by more than kConvergedChiSquare; the run with
// the lower chi^2 stands.
void StepwiseDiagnoser::iterate_refits(const DiagnosisStepRecord& s, std::vector<RefitRun>& refits) {
  for (int it = 0; it < options_.refit_iterations; ++it)
    if (!secant_round(s, refits)) return;
}

bool StepwiseDiagnoser::secant_round(const DiagnosisStepRecord& s, std::vector<RefitRun>& refits) {
  std::vector<RefitRun> next{refits.front()};  // its run is cached: no new run
  std::vector<std::size_t> of{0};
  for (std::size_t k = 1; k < refits.size(); ++k) {
    const RefitRun& c = refits[k];
    if (!c.failure.empty()) continue;
    const auto lr = secant_refit(s.lin.base, s.lin.jacobian, c.signature,
                                 refit_step(out_.keys, s.model, c.plan.model, c.effect), c.residual);
    if (!lr) continue;
    RefitRun n = c;
    n.plan = refit_plan(out_.keys, s.model, *lr, c.effect);
    if (c.effect) n.effect_value = n.plan.model.kept.back().second;
    next.push_back(std::move(n));
    of.push_back(k);
  }
  if (next.size() == 1) return false;
  try {
    run_refits(next, s.lin.base.values.size());
  } catch (const std::exception& e) {  // the base refit did not run: the linear refits stand
    log_ << fmt::format("diagnose: secant iteration left out: {}\n", e.what());
    return false;
  }
  bool improved = false;
  for (std::size_t j = 1; j < next.size(); ++j)
    if (next[j].failure.empty() && next[j].chi_square < refits[of[j]].chi_square) {
      improved = improved || next[j].chi_square < refits[of[j]].chi_square - kConvergedChiSquare;
      next[j].secant_steps = refits[of[j]].secant_steps + 1;
      refits[of[j]] = std::move(next[j]);
    }
  return improved;
}

// Bonferroni over the path: the alpha-to-enter of 0.05 is shared by every nameable refit tried so
// far, this step's and the earlier steps' (the family-wise level of the path).
void StepwiseDiagnoser::decide(DiagnosisStepRecord& s) {
  std::vector<RefitOutcome> refits;
  for (std::size_t k = 1; k < s.refits.size(); ++k)
    refits.push_back({s.refits[k].name, s.refits[k].chi_square, s.refits[k].nrmse,
                      s.refits[k].effect->identifiable_at(data_.coverage()),
                      seed_resolution_p(s.refits.front(), s.refits[k])});
  ConfirmationRule rule;
  rule.earlier_refits = refits_tried_;
  for (const auto& r : refits) refits_tried_ += r.identifiable ? 1 : 0;
  const RefitRun& base_refit = s.refits.front();
  s.decision = decide_from_refits({"base refit", base_refit.chi_square, base_refit.nrmse}, refits,
                                  s.lin.base.values.size(), s.lin.jacobian.size(), rule);
}

void StepwiseDiagnoser::record(const DiagnosisStepRecord& s, const RefitRun& refit, bool named) {
  const RefitRun& base_refit = s.refits.front();
  const double dof = static_cast<double>(s.lin.base.values.size() - s.lin.jacobian.size() - 1);
  out_.path.push_back({refit.name, refit.effect_value, base_refit.chi_square, refit.chi_square, base_refit.nrmse,
                       refit.nrmse, chi_square_survival(refit.chi_square, dof), named});
  out_.model = refit.plan.model;
}

// A name ends the path; so does a base refit within noise: on the first step the model is
// adequate, after a kept effect the kept effect re-sized around itself fits (not a name: its own
// refit did not reach noise). A kept effect becomes the next step's model, carried towards its own
// minimum first; on the last step it is the last word, a partial explanation.
StepwiseDiagnoser::Next StepwiseDiagnoser::follow_decision(DiagnosisStepRecord& s, bool last) {
  const ConfirmationDecision& d = s.decision;
  if (d.verdict != kAdequate && d.verdict != kUnexplained) {
    record(s, refit_named(s, d.verdict), true);
    return Next::Stop;
  }
  if (d.verdict == kAdequate) {
    if (out_.path.empty()) out_.verdict = kAdequate;
    else out_.resized_p = d.base_p;
    return Next::Stop;
  }
  if (d.kept.empty()) return Next::Stop;
  if (last) {
    record(s, refit_named(s, d.kept), false);
    return Next::Stop;
  }
  std::vector<RefitRun> kept{s.refits.front(), refit_named(s, d.kept)};
  iterate_refits(s, kept);
  s.kept_converged = kept.back();
  record(s, kept.back(), false);
  return Next::Step;
}

}  // namespace

SetDiagnosisResult diagnose_set(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene,
                                std::vector<CandidateEffect> library, const SetDiagnosisOptions& options,
                                std::ostream& log) {
  // Every report starts from the first step, which needs a candidate to linearise.
  if (library.empty()) throw std::invalid_argument("diagnose: no candidate effects to try (the library is empty)");
  SetDiagnosisResult out;
  out.keys = options.params;
  for (const auto& k : out.keys) out.model.parameters.push_back(simulator.parameter(scene, k));
  out.effects = plausible_on_base_run(std::move(library), simulator, data, step_plan(scene, out.keys, out.model),
                                      out.scaled_sizes, log);
  StepwiseDiagnoser(simulator, data, scene, options, out, log).run();
  for (const auto& s : out.steps) {
    if (!s.refits.empty() && s.refits.front().plan.base_at_bound) out.base_out_of_range = true;
    if (out.unidentifiable.empty()) out.unidentifiable = s.decision.unidentifiable;
  }
  out.health = simulator.health();
  return out;
}

}  // namespace shard::measure
