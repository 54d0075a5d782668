#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>

#include "shard/measure/contrast_diagnosis.hpp"
#include "shard/measure/effect_scaling.hpp"

namespace shard::measure {

std::vector<CandidateEffect> scaled_to_base_run(std::vector<CandidateEffect> effects, ContrastStudy& study,
                                               std::string& described, std::ostream& log) {
  described.clear();
  if (std::none_of(effects.begin(), effects.end(), [](const auto& e) { return !e.plausible_from.empty(); }))
    return effects;
  const auto base = study.simulate({study.base()}, log);
  const TestScales scales = base_run_scales(base.front().curves);
  effects = with_test_plausible(std::move(effects), scales);
  described = describe_scaled_plausible(effects, scales);
  log << "diagnose: plausible sizes from the base run:\n" << described;
  return effects;
}

std::vector<std::optional<ContrastStudy::Simulated>> simulate_each(ContrastStudy& study,
                                                                   const std::vector<ModelPlan>& models,
                                                                   const std::function<std::string(std::size_t)>& label,
                                                                   std::ostream& log) {
  std::vector<std::optional<ContrastStudy::Simulated>> runs(models.size());
  try {
    auto all = study.simulate(models, log);
    for (std::size_t m = 0; m < models.size(); ++m) runs[m] = std::move(all[m]);
  } catch (const std::exception&) {
    for (std::size_t m = 0; m < models.size(); ++m) try {
        runs[m] = std::move(study.simulate({models[m]}, log).front());
      } catch (const std::exception& e) {
        const std::string what = e.what();
        log << fmt::format("diagnose: {} did not run and is left out: {}\n", label(m), what.substr(0, what.find('\n')));
      }
  }
  return runs;
}

namespace {

// One effect of one set, simulated at its fitted size.
struct Trial {
  std::size_t effect = 0;
  double scale = 0;
  ContrastStudy::Simulated run;
  bool has_run = false;
  bool failed = false;
};
using SetTrials = std::vector<std::vector<Trial>>;  // [set][trial]

// Each set's best `count` effects of the linear fit (none for a set of no difference).
SetTrials first_trials(const std::vector<SetDiagnosis>& sets, const std::vector<CandidateEffect>& effects, int count) {
  SetTrials trials(sets.size());
  for (std::size_t s = 0; s < sets.size(); ++s) {
    if (sets[s].linear.verdict == kNoDifference) continue;  // nothing to confirm
    int taken = 0;
    for (const auto& f : sets[s].linear.fits) {
      if (taken >= count) break;
      if (f.scale == 0 || !(f.drop > 0)) continue;
      for (std::size_t e = 0; e < effects.size(); ++e)
        if (effects[e].name == f.name) trials[s].push_back({e, f.scale, {}, false});
      ++taken;
    }
  }
  return trials;
}

class Confirmation {
 public:
  Confirmation(ContrastStudy& study, const std::vector<CandidateEffect>& effects, const ContrastStudy::Simulated& base,
               std::vector<SetDiagnosis>& sets, int count)
      : study_(study), effects_(effects), base_(base), sets_(sets), trials_(first_trials(sets, effects, count)) {}

  // One batch: trials without a run are run, and a run whose simulated contrast asks for a size
  // more than 20 % away is run again there. False when nothing was left to run.
  bool pass(int index, std::ostream& log) {
    std::vector<ModelPlan> models;
    std::vector<std::pair<std::size_t, std::size_t>> owner;
    for (std::size_t s = 0; s < sets_.size(); ++s)
      for (std::size_t k = 0; k < trials_[s].size(); ++k) {
        Trial& t = trials_[s][k];
        if (t.has_run && !resized(sets_[s], t)) continue;
        models.push_back(with_effect(study_.base(), effects_[t.effect], effects_[t.effect].value_at(t.scale)));
        owner.emplace_back(s, k);
      }
    if (models.empty()) return false;
    log << fmt::format("diagnose: confirmation pass {}: {} runs of effects at their fitted sizes\n", index + 1, models.size());
    auto runs = simulate_each(
        study_, models,
        [&](std::size_t m) {
          const Trial& t = trials_[owner[m].first][owner[m].second];
          return fmt::format("{} at {:.4g}", effects_[t.effect].name, effects_[t.effect].value_at(t.scale));
        },
        log);
    for (std::size_t m = 0; m < models.size(); ++m) {
      Trial& t = trials_[owner[m].first][owner[m].second];
      if (runs[m]) {
        t.run = std::move(*runs[m]);
        t.has_run = true;
      } else {
        t.failed = true;
      }
    }
    for (auto& per_set : trials_) std::erase_if(per_set, [](const Trial& t) { return t.failed; });
    return true;
  }

  // Each set decided on its simulated contrasts; the named (or closest) effect's run shown.
  void decide(const ContrastOptions& options) {
    for (std::size_t s = 0; s < sets_.size(); ++s)
      if (!trials_[s].empty()) decide_set(sets_[s], trials_[s], options);
  }

 private:
  EffectSignature signature_of(const SetDiagnosis& d, const Trial& t) const {
    const CandidateEffect& e = effects_[t.effect];
    return EffectSignature{e.name, e.value_at(t.scale) - e.neutral, study_.model_contrast(d.contrast, t.run, base_), 1, 1,
                           e.identifiable_at(study_.rate_count(d.contrast))};
  }

  // The simulated contrast at this size, scaled by a*, fits best: a new size when a* is more
  // than 20 % from 1 (an effect's signature is not linear in its size).
  bool resized(const SetDiagnosis& d, Trial& t) const {
    const EffectSignature sig = signature_of(d, t);
    const auto fit = decide_contrast(d.contrast.difference, d.contrast.weight,
                                     {{sig.name, sig.trial_size, sig.signature, 0, 1e9}}, study_.dof());
    const double a = fit.fits.front().scale;
    if (!(std::abs(a - 1) > 0.2) || a == 0) return false;
    const CandidateEffect& e = effects_[t.effect];
    t.scale = std::clamp(t.scale * a, e.scale_min(), e.scale_max());
    return true;
  }

  void decide_set(SetDiagnosis& d, const std::vector<Trial>& trials, const ContrastOptions& options) const {
    std::vector<EffectSignature> sig;
    for (const auto& t : trials) sig.push_back(signature_of(d, t));
    d.decision = decide_contrast(d.contrast.difference, d.contrast.weight, sig, study_.dof(), options);
    d.confirmed_values.clear();
    for (auto& f : d.decision.fits)
      for (const auto& t : trials)
        if (effects_[t.effect].name == f.name) {
          d.confirmed_values.push_back(effects_[t.effect].value_at(t.scale));
          // A run's size is fixed; it is at a bound when the size it was run at is.
          f.at_bound = t.scale <= effects_[t.effect].scale_min() || t.scale >= effects_[t.effect].scale_max();
        }
    // A named effect is shown with its run; for an unexplained difference the closest effect, so
    // the plot shows how far the library gets; nothing when there is no difference to explain.
    if (d.decision.verdict == kNoDifference) return;
    const std::string& show =
        d.decision.verdict == kUnexplainedDifference ? d.decision.fits.front().name : d.decision.verdict;
    for (const auto& t : trials)
      if (effects_[t.effect].name == d.decision.fits.front().name) d.closest = SetDiagnosis::ConfirmedRun{t.effect, t.scale, t.run};
    for (const auto& t : trials)
      if (effects_[t.effect].name == show) {
        d.after = study_.curve_contrast(d.contrast, t.run, base_);
        d.after_effect = show;
        d.after_components = study_.model_contrast(d.contrast, t.run, base_);
        d.after_value = effects_[t.effect].value_at(t.scale);
      }
  }

  ContrastStudy& study_;
  const std::vector<CandidateEffect>& effects_;
  const ContrastStudy::Simulated& base_;
  std::vector<SetDiagnosis>& sets_;
  SetTrials trials_;
};

}  // namespace

void confirm_contrasts(ContrastStudy& study, const std::vector<CandidateEffect>& effects,
                       const ContrastStudy::Simulated& base, std::vector<SetDiagnosis>& sets, int count, int iterations,
                       ContrastOptions decide, std::ostream& log) {
  Confirmation confirmation(study, effects, base, sets, count);
  for (int pass = 0; pass < iterations; ++pass)
    if (!confirmation.pass(pass, log)) break;
  decide.tried = effects.size();
  confirmation.decide(decide);
}

}  // namespace shard::measure
