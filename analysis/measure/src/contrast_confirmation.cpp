#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "shard/measure/contrast_diagnosis.hpp"
#include "shard/measure/effect_scaling.hpp"
#include "square_matrix.hpp"

namespace shard::measure {

std::vector<CandidateEffect> scaled_to_base_run(std::vector<CandidateEffect> effects, ContrastStudy& study,
                                               std::string& described, std::ostream& log) {
  described.clear();
  if (std::none_of(effects.begin(), effects.end(), [](const auto& e) { return !e.plausible_from.empty(); }))
    return effects;
  const TestScales scales = base_run_scales(simulate_base(study, log).curves);
  effects = with_test_plausible(std::move(effects), scales);
  described = describe_scaled_plausible(effects, scales);
  log << "diagnose: plausible sizes from the base run:\n" << described;
  return effects;
}

ContrastStudy::Simulated simulate_base(ContrastStudy& study, std::ostream& log) {
  try {
    return std::move(study.simulate({study.base()}, log).front());
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("the base model: {}. Fix: run the base scene at that rate and look at its "
                                         "curve (shard bending run.h5, shard bending-rate-check), or leave out "
                                         "the sets tested there",
                                         e.what()));
  }
}

std::vector<std::optional<ContrastStudy::Simulated>> simulate_each(ContrastStudy& study,
                                                                   const std::vector<ModelPlan>& models,
                                                                   const std::function<std::string(std::size_t)>& label,
                                                                   std::ostream& log, const std::string& command,
                                                                   std::vector<std::string>* failures) {
  std::vector<std::optional<ContrastStudy::Simulated>> runs(models.size());
  if (failures) failures->assign(models.size(), {});
  try {
    auto all = study.simulate(models, log);
    for (std::size_t m = 0; m < models.size(); ++m) runs[m] = std::move(all[m]);
  } catch (const std::exception&) {
    for (std::size_t m = 0; m < models.size(); ++m) try {
        runs[m] = std::move(study.simulate({models[m]}, log).front());
      } catch (const std::exception& e) {
        const std::string what = e.what(), reason = what.substr(0, what.find('\n'));
        log << fmt::format("{}: {} gave no usable run and is left out: {}\n", command, label(m), reason);
        if (failures) (*failures)[m] = reason;
      }
  }
  return runs;
}

namespace {

// A run's size (in trial steps from neutral) and its simulated contrast.
struct SizedContrast {
  double scale = 0;
  std::vector<double> contrast;
};

// One effect of one set, simulated at its fitted size. `previous` is the run before the latest,
// the secant's other point; `best` the run whose contrast fitted the set best so far (an effect's
// response bends with its size, so a step can overshoot).
struct Trial {
  std::size_t effect = 0;
  double scale = 0;
  ContrastStudy::Simulated run;
  bool has_run = false;
  bool failed = false;
  bool settled = false;  // no further size: a resized run failed, and the best run stands
  std::optional<SizedContrast> previous;
  struct Best {
    double scale = 0, chi_square = 0;
    ContrastStudy::Simulated run;
  };
  std::optional<Best> best;
};

// A size step is not worth a run when it moves the size by less than this share (the pair step's
// limit as well): the decision refits the run's contrast linearly around it anyway.
constexpr double kResizeShare = 0.1;

// A probe's step in size: far enough that a rough response shows its trend, near enough that two
// steps span the factor of two the secant's clamp allows.
constexpr double kProbeFactor = 1.41421356237;

// A confirmation run's size: the data choose it, so it stays within the effect's free sizes.
double within_reach(const CandidateEffect& e, double scale) {
  return std::clamp(scale, lowest_free_size(e), highest_free_size(e));
}

// The size minimising the generalised chi^2 on the secant through two sized runs (t(s) linear
// between them), kept within half and twice the latest size so one bent response cannot throw it
// far. None when the two contrasts do not differ along the weight.
std::optional<double> secant_size(const SizedContrast& a, const SizedContrast& b, const std::vector<double>& d,
                                  const std::vector<std::vector<double>>& w) {
  if (b.scale == a.scale) return std::nullopt;
  const auto vector = [](const std::vector<double>& v) {
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  };
  const Eigen::VectorXd slope = (vector(b.contrast) - vector(a.contrast)) / (b.scale - a.scale);
  const Eigen::VectorXd weighted = to_matrix(w) * slope;
  const double curvature = slope.dot(weighted);
  if (!(curvature > 0)) return std::nullopt;
  const double next = b.scale + weighted.dot(vector(d) - vector(b.contrast)) / curvature;
  const double lo = std::min(0.5 * b.scale, 2 * b.scale), hi = std::max(0.5 * b.scale, 2 * b.scale);
  return std::clamp(next, lo, hi);
}

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
        if (effects[e].name == f.name) {
          Trial& t = trials[s].emplace_back();
          t.effect = e;
          t.scale = within_reach(effects[e], f.scale);
        }
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

  // One batch: trials without a run are run, and a run whose secant asks for a size more than
  // kResizeShare away is run again there. False when nothing was left to run.
  bool pass(int index, std::ostream& log) {
    std::vector<SizedRun> wanted;
    for (std::size_t s = 0; s < sets_.size(); ++s)
      for (std::size_t k = 0; k < trials_[s].size(); ++k) {
        Trial& t = trials_[s][k];
        if (t.has_run && (t.settled || !resized(sets_[s], t))) continue;
        wanted.push_back({s, k, t.scale});
      }
    if (wanted.empty()) return false;
    auto runs = run_sized(wanted, fmt::format("confirmation pass {}: {} runs of effects at their fitted sizes", index + 1,
                                              wanted.size()),
                          log);
    for (std::size_t m = 0; m < wanted.size(); ++m) {
      Trial& t = trials_[wanted[m].set][wanted[m].trial];
      if (runs[m]) {
        t.run = std::move(*runs[m]);
        t.has_run = true;
      } else if (t.best) {  // a size the plugin refuses or that goes unstable: the best run stands
        t.scale = t.best->scale;
        t.run = t.best->run;
        t.settled = true;
      } else {
        t.failed = true;
      }
    }
    for (auto& per_set : trials_) std::erase_if(per_set, [](const Trial& t) { return t.failed; });
    return true;
  }

  // Bracketing probes beyond the secant. A brittle beam's response to an effect is not smooth in
  // its size (which bond breaks first moves the peak), so the secant can settle where the
  // contrast's linear part balances while a larger or smaller size fits the whole contrast. A set
  // whose closest effect takes at least min_share of its difference but leaves a remainder beyond
  // noise has that effect run kProbeFactor either side of its best size, then further the way
  // that fitted better, `rounds` runs in all on each side taken; the best-fitting run stands.
  void probe(int rounds, const ContrastOptions& options, std::ostream& log) {
    std::vector<Probe> probes = probes_wanted(options);
    for (int round = 0; round < rounds && !probes.empty(); ++round) {
      std::vector<SizedRun> wanted;
      std::vector<std::size_t> owner;  // the probe of each run
      for (std::size_t p = 0; p < probes.size(); ++p)
        for (const double scale : probes[p].next_scales(trials_[probes[p].set][probes[p].trial], effects_)) {
          wanted.push_back({probes[p].set, probes[p].trial, scale});
          owner.push_back(p);
        }
      if (wanted.empty()) break;
      auto runs = run_sized(
          wanted, fmt::format("size probes, round {}: {} runs either side of the best size", round + 1, wanted.size()),
          log);
      std::vector<int> improved(probes.size(), 0);
      for (std::size_t m = 0; m < wanted.size(); ++m) {
        if (!runs[m]) continue;
        const Probe& pr = probes[owner[m]];
        Trial& t = trials_[pr.set][pr.trial];
        const SetDiagnosis& d = sets_[pr.set];
        const double scale = wanted[m].scale;
        const double chi_square = run_chi_square(d, signature_of(d, t.effect, scale, *runs[m]));
        if (chi_square < t.best->chi_square) {
          t.best = Trial::Best{scale, chi_square, std::move(*runs[m])};
          improved[owner[m]] = std::abs(scale) > std::abs(pr.centre) ? 1 : -1;
        }
      }
      for (std::size_t p = 0; p < probes.size(); ++p) probes[p].advance(improved[p]);
      std::erase_if(probes, [](const Probe& pr) { return pr.done; });
    }
  }

  // Each set decided on its best-fitting runs; the named (or closest) effect's run shown.
  void decide(const ContrastOptions& options) {
    for (std::size_t s = 0; s < sets_.size(); ++s) {
      for (Trial& t : trials_[s]) take_best(sets_[s], t);
      if (!trials_[s].empty()) decide_set(sets_[s], trials_[s], options);
    }
  }

 private:
  // A trial's effect at a size of its own (the trial's, or a probe's).
  struct SizedRun {
    std::size_t set = 0, trial = 0;
    double scale = 0;
  };

  // One batch of sized runs, listed in the log under `header`; a failed run is left out (empty).
  std::vector<std::optional<ContrastStudy::Simulated>> run_sized(const std::vector<SizedRun>& wanted,
                                                                 const std::string& header, std::ostream& log) {
    std::vector<ModelPlan> models;
    std::vector<std::string> labels;
    for (const SizedRun& r : wanted) {
      const CandidateEffect& e = effects_[trials_[r.set][r.trial].effect];
      models.push_back(with_effect(study_.base(), e, e.value_at(r.scale)));
      labels.push_back(fmt::format("{}: {} at {:.4g}", study_.sets().names[sets_[r.set].set], e.name, e.value_at(r.scale)));
    }
    log << "diagnose: " << header << "\n";
    for (const auto& l : labels) log << "  " << l << "\n";
    return simulate_each(study_, models, [&](std::size_t m) { return labels[m]; }, log);
  }

  EffectSignature signature_of(const SetDiagnosis& d, std::size_t effect, double scale,
                               const ContrastStudy::Simulated& run) const {
    const CandidateEffect& e = effects_[effect];
    return EffectSignature{e.name, e.value_at(scale) - e.neutral, study_.model_contrast(d.contrast, run, base_), 1, 1,
                           e.identifiable_at(d.contrast.coverage)};
  }
  EffectSignature signature_of(const SetDiagnosis& d, const Trial& t) const {
    return signature_of(d, t.effect, t.scale, t.run);
  }

  // The set's chi^2 left by the run's contrast as simulated: what the decision reads.
  double run_chi_square(const SetDiagnosis& d, const EffectSignature& sig) const {
    return decide_contrast(d.contrast.difference, d.contrast.weight, {sig}, study_.noise()).fits.front().chi_square;
  }

  void note_best(const SetDiagnosis& d, Trial& t, const EffectSignature& sig) const {
    const double chi_square = run_chi_square(d, sig);
    if (!t.best || chi_square < t.best->chi_square) t.best = Trial::Best{t.scale, chi_square, t.run};
  }

  void take_best(const SetDiagnosis& d, Trial& t) const {
    note_best(d, t, signature_of(d, t));
    t.scale = t.best->scale;
    t.run = t.best->run;
  }

  // The next size: on the secant through this run and the one before it, or for the first run
  // through neutral (whose contrast is zero); a new run when that moves the size by more than
  // kResizeShare. Keeps the best-fitting run of those made.
  bool resized(const SetDiagnosis& d, Trial& t) const {
    const EffectSignature sig = signature_of(d, t);
    note_best(d, t, sig);
    const SizedContrast latest{t.scale, sig.signature};
    const SizedContrast origin{0, std::vector<double>(sig.signature.size(), 0.0)};
    const auto next = secant_size(t.previous.value_or(origin), latest, d.contrast.difference, d.contrast.weight);
    if (!next) return false;
    const CandidateEffect& e = effects_[t.effect];
    const double scale = within_reach(e, *next);
    if (!(std::abs(scale - t.scale) > kResizeShare * std::abs(t.scale)) || scale == 0) return false;
    t.previous = latest;
    t.scale = scale;
    return true;
  }

  // One set's probe of its closest effect: multiplicative steps of the size in trial steps from
  // neutral, which keeps the size on its side of neutral.
  struct Probe {
    std::size_t set = 0, trial = 0;
    double centre = 0;   // the best size when the last round was planned
    int direction = 0;   // 0: both sides still to try; +1 / -1: further out / further in
    bool done = false;

    std::vector<double> next_scales(const Trial& t, const std::vector<CandidateEffect>& effects) {
      centre = t.best->scale;
      const CandidateEffect& e = effects[t.effect];
      std::vector<double> scales;
      const auto take = [&](double factor) {
        const double s = within_reach(e, centre * factor);
        if (std::abs(s - centre) > kResizeShare * std::abs(centre)) scales.push_back(s);
      };
      if (direction >= 0) take(kProbeFactor);
      if (direction <= 0) take(1 / kProbeFactor);
      return scales;
    }
    // `improved`: the side whose run fitted better than the best before it (0: neither, or no run).
    void advance(int improved) {
      if (improved == 0) done = true;
      direction = improved;
    }
  };

  // The closest effect as run already carries a name by its curve (contrast_diagnosis.hpp): no
  // probe needed.
  bool named_by_its_curve(const SetDiagnosis& d, const Trial& t, double share, const ContrastOptions& options) const {
    return share >= options.curve_name_share &&
           curve_bears_out(study_.curve_contrast(d.contrast, t.run, base_), d.before, options) &&
           !component_missed_by_curve_name(d.contrast, study_.model_contrast(d.contrast, t.run, base_), options);
  }

  std::vector<Probe> probes_wanted(const ContrastOptions& options) {
    std::vector<Probe> probes;
    for (std::size_t s = 0; s < sets_.size(); ++s) {
      if (trials_[s].empty()) continue;
      std::vector<EffectSignature> sig;
      for (Trial& t : trials_[s]) {
        take_best(sets_[s], t);
        sig.push_back(signature_of(sets_[s], t));
      }
      const ContrastDecision tentative =
          decide_contrast(sets_[s].contrast.difference, sets_[s].contrast.weight, sig, study_.noise(), options);
      if (tentative.fits.empty() || !(tentative.chi_square > 0)) continue;
      const ContrastFit& closest = tentative.fits.front();
      if (closest.drop < options.min_share * tentative.chi_square || closest.p_after >= options.remaining_p) continue;
      for (std::size_t k = 0; k < trials_[s].size(); ++k)
        if (effects_[trials_[s][k].effect].name == closest.name && trials_[s][k].scale != 0 &&
            !named_by_its_curve(sets_[s], trials_[s][k], closest.drop / tentative.chi_square, options))
          probes.push_back(Probe{s, k});
    }
    return probes;
  }

  void decide_set(SetDiagnosis& d, const std::vector<Trial>& trials, const ContrastOptions& options) const {
    std::vector<EffectSignature> sig;
    for (const auto& t : trials) sig.push_back(signature_of(d, t));
    d.decision = decide_contrast(d.contrast.difference, d.contrast.weight, sig, study_.noise(), options);
    d.confirmed_values.clear();
    for (auto& f : d.decision.fits)
      for (const auto& t : trials)
        if (effects_[t.effect].name == f.name) {
          d.confirmed_values.push_back(effects_[t.effect].value_at(t.scale));
          // A run's size is fixed; it is at a bound when the size it was run at is.
          f.at_bound = t.scale <= lowest_free_size(effects_[t.effect]) || t.scale >= highest_free_size(effects_[t.effect]);
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
                       int probes, ContrastOptions decide, std::ostream& log) {
  Confirmation confirmation(study, effects, base, sets, count);
  for (int pass = 0; pass < iterations; ++pass)
    if (!confirmation.pass(pass, log)) break;
  decide.tried = effects.size();
  confirmation.probe(probes, decide, log);
  confirmation.decide(decide);
}

}  // namespace shard::measure
