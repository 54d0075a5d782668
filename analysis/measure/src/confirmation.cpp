#include "shard/measure/confirmation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shard/measure/statistics.hpp"

namespace shard::measure {

ConfirmationDecision decide_from_refits(const RefitOutcome& base, const std::vector<RefitOutcome>& refits,
                                        std::size_t m, std::size_t p, const ConfirmationRule& rule) {
  if (m < p + 2) throw std::invalid_argument("decide_from_refits: need at least two residual components beyond the base parameters");
  const double base_chi2 = base.chi_square;
  ConfirmationDecision d;
  d.excess = base_chi2 - static_cast<double>(m - p);
  d.base_p = chi_square_survival(base_chi2, static_cast<double>(m - p));
  d.base_nrmse = base.nrmse;
  const std::size_t nameable = static_cast<std::size_t>(
      std::count_if(refits.begin(), refits.end(), [](const RefitOutcome& r) { return r.identifiable; }));
  const double drop_level = rule.drop_p / static_cast<double>(std::max<std::size_t>(1, nameable + rule.earlier_refits));
  const double log_m = std::log(static_cast<double>(m));
  const ConfirmedEffect* best_named = nullptr;
  const ConfirmedEffect* best_kept = nullptr;
  const ConfirmedEffect* best_any = nullptr;
  d.effects.reserve(refits.size());
  for (const auto& r : refits) {
    ConfirmedEffect e;
    e.name = r.name;
    e.chi_square = r.chi_square;
    e.nrmse = r.nrmse;
    const double drop = base_chi2 - r.chi_square;
    e.share_explained = d.excess > 0 ? drop / d.excess : 0;
    e.delta_aic = -drop + 2;
    e.delta_bic = -drop + log_m;
    // A refit that could not be simulated (infinite chi^2) explains nothing.
    e.p_after = std::isfinite(r.chi_square) ? chi_square_survival(r.chi_square, static_cast<double>(m - p - 1)) : 0;
    e.p_drop = drop > 0 && std::isfinite(drop) ? chi_square_survival(drop, 1) : 1;
    // NaN on either side compares false: the rule needs both NRMSEs.
    e.nrmse_rose = r.nrmse > base.nrmse;
    e.seed_p = r.seed_p;
    e.resolved = r.seed_p < rule.seed_p;
    e.qualifies = d.excess > 0 && e.share_explained >= rule.min_explained && e.delta_aic < 0 && e.delta_bic < 0 &&
                  e.p_drop < drop_level && (rule.nrmse_may_rise || !e.nrmse_rose) && e.resolved;
    e.named = e.qualifies && e.p_after > rule.remaining_p;
    e.identifiable = r.identifiable;
    if (!e.identifiable) {
      e.would_name = e.named;
      e.qualifies = e.named = false;
    }
    d.effects.push_back(e);
  }
  for (const auto& e : d.effects) {
    if (e.named && (!best_named || e.chi_square < best_named->chi_square)) best_named = &e;
    if (e.qualifies && (!best_kept || e.chi_square < best_kept->chi_square)) best_kept = &e;
    if (e.chi_square < base_chi2 && (!best_any || e.chi_square < best_any->chi_square)) best_any = &e;
  }
  if (best_named) {
    d.verdict = best_named->name;
    for (const auto& e : d.effects)
      if (&e != best_named && e.share_explained >= rule.min_explained &&
          e.chi_square <= best_named->chi_square + rule.rival_chi_square)
        d.rivals.push_back(e.name);
  } else if (d.base_p > rule.remaining_p) {
    d.verdict = kAdequate;
  } else {
    d.verdict = kUnexplained;
    if (best_any) d.best_partial = best_any->name;
    // The kept refit is the next step's base, not a conclusion. Refits within rival_chi_square of
    // the best are not told apart by chi^2; of those, the one whose curve is closest (NRMSE) goes
    // on. The two-effect test's first step: compliance 29.1 (NRMSE 7.3 %) against softening 28.0
    // (11.4 %, at its refit bound); softening kept first left compliance unseen at step 2.
    if (best_kept)
      for (const auto& e : d.effects)
        if (e.qualifies && e.chi_square <= best_kept->chi_square + rule.rival_chi_square && e.nrmse < best_kept->nrmse)
          best_kept = &e;
    if (best_kept) d.kept = best_kept->name;
    const ConfirmedEffect* unidentifiable = nullptr;
    for (const auto& e : d.effects)
      if (e.would_name && (!unidentifiable || e.chi_square < unidentifiable->chi_square)) unidentifiable = &e;
    if (unidentifiable) d.unidentifiable = unidentifiable->name;
  }
  return d;
}

ConfirmationDecision decide_from_refits(double base_chi2, const std::vector<RefitOutcome>& refits, std::size_t m,
                                        std::size_t p, const ConfirmationRule& rule) {
  return decide_from_refits(RefitOutcome{"base refit", base_chi2}, refits, m, p, rule);
}

GainCredit credit_gain(double before, double base_only, double with_effect) {
  GainCredit c;
  c.total = before - with_effect;
  c.by_base = before - base_only;
  c.by_effect = base_only - with_effect;
  c.effect_p = c.by_effect > 0 ? chi_square_survival(c.by_effect, 1) : 1;
  c.effect_supported = c.by_effect > 2 && c.effect_p < 0.05;
  return c;
}

std::string stepwise_verdict(const std::vector<DiagnosisStep>& path) {
  if (path.empty() || !path.back().named) return kUnexplained;
  std::string v;
  for (const auto& s : path) v += (v.empty() ? "" : " + ") + s.effect;
  return v;
}

}  // namespace shard::measure
