// Two effects at once in the contrast diagnosis (docs/explanation/diagnosis.md,
// "Contrasts: two effects at once"): keep the closest single effect, add the next, judge what it adds.
#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <cmath>
#include <optional>
#include <ostream>

#include "shard/measure/contrast_diagnosis.hpp"

namespace shard::measure {

namespace {

// A signature in units of `unit` trial sizes, with the effect's range in those units (for a
// second effect, whose size the pair's fit chooses freely, at most kFarthestTrialSteps from neutral).
EffectSignature in_units(const CandidateEffect& e, std::vector<double> signature, double unit, bool second) {
  double lo = e.scale_min(), hi = e.scale_max();
  if (second) lo = lowest_free_size(e), hi = highest_free_size(e);
  lo /= unit, hi /= unit;
  if (unit < 0) std::swap(lo, hi);
  return {e.name, e.value_at(unit) - e.neutral, std::move(signature), lo, hi, true};
}

// A second effect's columns: its trial per trial size, and for an effect that moves both ways
// from the reference its mirror trial as well, each over its own side of neutral (the response
// is seldom symmetric); the pair's fit takes the side that leaves the smaller chi^2.
std::vector<EffectSignature> second_columns(const ContrastStudy& study, const SetDiagnosis& d, const CandidateEffect& e,
                                            const std::vector<ContrastStudy::Simulated>& trials, std::size_t plus,
                                            std::size_t mirror) {
  const ContrastStudy::Simulated& base = trials.front();
  EffectSignature up = in_units(e, study.model_contrast(d.contrast, trials[plus], base), 1.0, true);
  if (mirror == 0) return {up};
  EffectSignature down = up;
  down.signature = study.model_contrast(d.contrast, trials[mirror], base);
  for (double& x : down.signature) x = -x;  // per step towards plausible, read on the other side
  up.scale_min = 0, down.scale_max = 0;
  return {up, down};
}

struct PairTrial {
  std::size_t set = 0, second = 0;
  // The two columns of the linear fit: the first's confirmed contrast per confirmed size, the
  // second's trial contrast per trial size (each with its range in those units).
  EffectSignature first_column, second_column;
  double scale_first = 0, scale_second = 0;  // in trial sizes from neutral
  ContrastPairFit fit;                      // judged on the run once it has one
  std::optional<ContrastStudy::Simulated> run;
  bool stepped = false;  // a Gauss-Newton step has been taken from this run
};

ModelPlan pair_model(const ModelPlan& base, const std::vector<CandidateEffect>& effects, std::size_t first,
                     double scale_first, std::size_t second, double scale_second) {
  return with_effects(base, {{&effects[first], effects[first].value_at(scale_first)},
                             {&effects[second], effects[second].value_at(scale_second)}});
}

// The pair search over every set: candidates sought from each set's closest single effect, run,
// stepped once by Gauss-Newton, and the best named.
class PairSearch {
 public:
  PairSearch(ContrastStudy& study, const std::vector<CandidateEffect>& effects,
             const std::vector<ContrastStudy::Simulated>& trials, const std::vector<std::size_t>& mirror,
             std::vector<SetDiagnosis>& sets, const ContrastOptions& decide)
      : study_(study), effects_(effects), trials_(trials), mirror_(mirror), sets_(sets), decide_(decide) {}

  // The best `count` pairs of each set whose closest single effect has earned its place.
  bool seek(int count) {
    for (std::size_t s = 0; s < sets_.size(); ++s) {
      std::vector<PairTrial> mine = candidates(s);
      std::sort(mine.begin(), mine.end(), [](const auto& a, const auto& b) { return a.fit.chi_square < b.fit.chi_square; });
      if (mine.size() > static_cast<std::size_t>(count)) mine.resize(static_cast<std::size_t>(count));
      pairs_.insert(pairs_.end(), mine.begin(), mine.end());
    }
    return !pairs_.empty();
  }

  // One batch: each pair without a run is run; each run not yet stepped (and not named) gets a
  // Gauss-Newton step, run as a new candidate. False when nothing was left to run.
  bool pass(int index, std::ostream& log) {
    std::vector<ModelPlan> models;
    std::vector<std::size_t> owner;
    std::vector<PairTrial> new_trials;  // appended after the loop: `pairs_` must not grow under it
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      PairTrial& p = pairs_[k];
      if (!p.run) {
        models.push_back(model_of(p));
        owner.push_back(k);
      } else if (auto next = stepped(p)) {
        models.push_back(model_of(*next));
        owner.push_back(pairs_.size() + new_trials.size());
        new_trials.push_back(std::move(*next));  // the earlier run stays a candidate: the better is kept
      }
    }
    pairs_.insert(pairs_.end(), std::make_move_iterator(new_trials.begin()), std::make_move_iterator(new_trials.end()));
    if (models.empty()) return false;
    log << fmt::format("diagnose: two effects at once, pass {}: {} runs of pairs at their fitted sizes\n", index + 1,
                       models.size());
    auto runs = simulate_each(
        study_, models, [&](std::size_t m) { return pair_name(pairs_[owner[m]]); }, log);
    for (std::size_t m = 0; m < models.size(); ++m) {
      PairTrial& p = pairs_[owner[m]];
      if (!runs[m]) continue;
      p.run = std::move(runs[m]);
      judge(p);
      const CandidateEffect& first = effects_[sets_[p.set].closest->effect];
      log << fmt::format("diagnose: {}: {} = {:.4g} with {} = {:.4g}: chi^2 {:.1f} (p after {:.2g}), the second's drop p = {:.2g}\n",
                         study_.sets().names[sets_[p.set].set], first.name, first.value_at(p.scale_first),
                         effects_[p.second].name, effects_[p.second].value_at(p.scale_second), p.fit.chi_square,
                         p.fit.p_after, p.fit.p_drop);
    }
    std::erase_if(pairs_, [](const PairTrial& p) { return !p.run; });
    return true;
  }

  // As for single effects (decide_contrast): the lowest chi^2 among the pairs that pass is named;
  // when none passes, the lowest chi^2 is reported as tried.
  void adopt_best() {
    for (std::size_t s = 0; s < sets_.size(); ++s)
      if (const PairTrial* best = best_of(s)) adopt(sets_[s], *best);
  }

 private:
  std::vector<PairTrial> candidates(std::size_t s) {
    SetDiagnosis& d = sets_[s];
    if (d.decision.verdict != kUnexplainedDifference || !d.closest || d.decision.fits.empty()) return {};
    const ContrastFit& closest = d.decision.fits.front();
    if (!starts_a_pair(closest, d.decision.chi_square, effects_.size(), decide_) || d.closest->scale == 0) return {};
    const std::size_t f = d.closest->effect;
    const EffectSignature first = in_units(effects_[f], study_.model_contrast(d.contrast, d.closest->run, trials_.front()),
                                           d.closest->scale, false);
    std::vector<PairTrial> mine;
    for (std::size_t e = 0; e < effects_.size(); ++e) {
      if (e == f || !effects_[e].identifiable_at(d.contrast.coverage) || !combinable(effects_[f], effects_[e]))
        continue;
      ++d.seconds_tried;
      EffectSignature second;
      ContrastPairFit fit;
      for (const EffectSignature& column : second_columns(study_, d, effects_[e], trials_, 1 + e, mirror_[e])) {
        const ContrastPairFit f2 = fit_contrast_pair(d.contrast.difference, d.contrast.weight, first, column,
                                                     closest.chi_square, study_.noise(), decide_);
        if (second.name.empty() || f2.chi_square < fit.chi_square) second = column, fit = f2;
      }
      if (fit.scale_second == 0 || !(fit.drop > 0)) continue;
      mine.push_back({s, e, first, second, fit.scale_first * d.closest->scale, fit.scale_second, fit, std::nullopt});
    }
    return mine;
  }

  // A Gauss-Newton step from the pair's run: its residual on the two effects' columns per trial
  // size (the closest's confirmed contrast over its size, the second's trial run), each step kept
  // inside its effect's range. None when stepped before, named, or the step is small.
  std::optional<PairTrial> stepped(PairTrial& p) {
    SetDiagnosis& d = sets_[p.set];
    if (p.stepped || pair_is_named(p.fit, d.seconds_tried, decide_)) return std::nullopt;
    p.stepped = true;
    std::vector<double> residual = d.contrast.difference;
    const auto combined = study_.model_contrast(d.contrast, *p.run, trials_.front());
    for (std::size_t i = 0; i < residual.size(); ++i) residual[i] -= combined[i];
    EffectSignature c1 = p.first_column, c2 = p.second_column;
    const double x1 = p.scale_first / d.closest->scale, x2 = p.scale_second;
    c1.scale_min -= x1, c1.scale_max -= x1, c2.scale_min -= x2, c2.scale_max -= x2;
    const ContrastPairFit step = fit_contrast_pair(residual, d.contrast.weight, c1, c2, p.fit.chi_square, study_.noise(), decide_);
    const double next_first = (x1 + step.scale_first) * d.closest->scale, next_second = x2 + step.scale_second;
    // Not worth a run when the step is small against the sizes (the linear step's limit).
    if (std::abs(next_first - p.scale_first) <= 0.1 * std::abs(p.scale_first) &&
        std::abs(next_second - p.scale_second) <= 0.1 * std::abs(p.scale_second))
      return std::nullopt;
    PairTrial next = p;
    next.scale_first = next_first;
    next.scale_second = next_second;
    next.run.reset();
    next.stepped = false;
    return next;
  }

  void judge(PairTrial& p) {
    SetDiagnosis& d = sets_[p.set];
    ContrastPairFit sized = p.fit;
    sized.scale_first = p.scale_first;
    sized.scale_second = p.scale_second;
    // At a bound when a run's size is: the first at its range's ends, the second also at the
    // farthest trial step.
    const CandidateEffect& a = effects_[d.closest->effect];
    const CandidateEffect& b = effects_[p.second];
    auto at = [](double x, double lo, double hi) { return x <= lo + 1e-9 * std::abs(lo) || x >= hi - 1e-9 * std::abs(hi); };
    sized.at_bound = at(p.scale_first, a.scale_min(), a.scale_max()) ||
                     at(p.scale_second, lowest_free_size(b), highest_free_size(b));
    p.fit = judge_simulated_pair(d.contrast.difference, d.contrast.weight,
                                 study_.model_contrast(d.contrast, *p.run, trials_.front()), sized,
                                 d.decision.fits.front().chi_square, study_.noise(), decide_);
    // The first's column is its confirmed run's contrast: what it leaves is the residual the
    // second's move must lower.
    std::vector<double> left = d.contrast.difference;
    for (std::size_t i = 0; i < left.size(); ++i) left[i] -= p.first_column.signature[i];
    p.fit.p_seeds = seed_consistency_p(left, d.contrast.weight, study_.seed_moves(d.contrast, *p.run, d.closest->run));
  }

  const PairTrial* best_of(std::size_t s) const {
    const PairTrial* best = nullptr;
    for (const bool named_only : {true, false}) {
      for (const auto& p : pairs_)
        if (p.set == s && (!named_only || pair_is_named(p.fit, sets_[s].seconds_tried, decide_)) &&
            (!best || p.fit.chi_square < best->fit.chi_square))
          best = &p;
      if (best) break;
    }
    return best;
  }

  void adopt(SetDiagnosis& d, const PairTrial& best) {
    const CandidateEffect& first = effects_[d.closest->effect];
    const CandidateEffect& second = effects_[best.second];
    d.pair = best.fit;
    d.pair_values[0] = first.value_at(best.scale_first);
    d.pair_values[1] = second.value_at(best.scale_second);
    if (!pair_is_named(best.fit, d.seconds_tried, decide_)) return;
    d.decision.verdict = first.name + " + " + second.name;
    d.withheld.clear();  // the single name the curve withheld is now half of the pair's
    d.decision.rivals.clear();
    for (const auto& p : pairs_)
      if (p.set == best.set && p.second != best.second && pair_is_named(p.fit, d.seconds_tried, decide_) &&
          p.fit.chi_square - best.fit.chi_square < decide_.rival_chi_square &&
          std::find(d.decision.rivals.begin(), d.decision.rivals.end(), pair_name(p)) == d.decision.rivals.end())
        d.decision.rivals.push_back(pair_name(p));
    d.after = study_.curve_contrast(d.contrast, *best.run, trials_.front());
    d.after_effect = d.decision.verdict;
    d.after_components = study_.model_contrast(d.contrast, *best.run, trials_.front());
  }

  ModelPlan model_of(const PairTrial& p) const {
    return pair_model(study_.base(), effects_, sets_[p.set].closest->effect, p.scale_first, p.second, p.scale_second);
  }
  std::string pair_name(const PairTrial& p) const {
    return effects_[sets_[p.set].closest->effect].name + " + " + effects_[p.second].name;
  }

  ContrastStudy& study_;
  const std::vector<CandidateEffect>& effects_;
  const std::vector<ContrastStudy::Simulated>& trials_;  // [0]: the base
  const std::vector<std::size_t>& mirror_;
  std::vector<SetDiagnosis>& sets_;
  const ContrastOptions& decide_;
  std::vector<PairTrial> pairs_;
};

}  // namespace

void confirm_contrast_pairs(ContrastStudy& study, const std::vector<CandidateEffect>& effects,
                            const std::vector<ContrastStudy::Simulated>& trials, const std::vector<std::size_t>& mirror,
                            std::vector<SetDiagnosis>& sets,
                            int count, int iterations, ContrastOptions decide, std::ostream& log) {
  PairSearch search(study, effects, trials, mirror, sets, decide);
  if (!search.seek(count)) return;
  for (int pass = 0; pass < std::max(1, iterations); ++pass)
    if (!search.pass(pass, log)) break;
  search.adopt_best();
}

}  // namespace shard::measure
