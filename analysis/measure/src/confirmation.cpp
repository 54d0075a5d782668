#include "shard/measure/confirmation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shard/measure/statistics.hpp"

namespace shard::measure {

ConfirmationDecision decide_from_refits(double base_chi2, const std::vector<RefitOutcome>& refits, std::size_t m,
                                        std::size_t p, const ConfirmationRule& rule) {
  if (m < p + 2) throw std::invalid_argument("decide_from_refits: need at least two residual components beyond the base parameters");
  ConfirmationDecision d;
  d.excess = base_chi2 - static_cast<double>(m - p);
  d.base_p = chi_square_survival(base_chi2, static_cast<double>(m - p));
  const double drop_level = rule.drop_p / static_cast<double>(std::max<std::size_t>(1, refits.size()));
  const double log_m = std::log(static_cast<double>(m));
  const ConfirmedEffect* best_named = nullptr;
  const ConfirmedEffect* best_any = nullptr;
  d.effects.reserve(refits.size());
  for (const auto& r : refits) {
    ConfirmedEffect e;
    e.name = r.name;
    e.chi_square = r.chi_square;
    const double drop = base_chi2 - r.chi_square;
    e.share_explained = d.excess > 0 ? drop / d.excess : 0;
    e.delta_aic = -drop + 2;
    e.delta_bic = -drop + log_m;
    // A refit that could not be simulated (infinite chi^2) explains nothing.
    e.p_after = std::isfinite(r.chi_square) ? chi_square_survival(r.chi_square, static_cast<double>(m - p - 1)) : 0;
    e.p_drop = drop > 0 && std::isfinite(drop) ? chi_square_survival(drop, 1) : 1;
    e.named = d.excess > 0 && e.share_explained >= rule.min_explained && e.delta_aic < 0 && e.delta_bic < 0 &&
              e.p_drop < drop_level && e.p_after > rule.remaining_p;
    d.effects.push_back(e);
  }
  for (const auto& e : d.effects) {
    if (e.named && (!best_named || e.chi_square < best_named->chi_square)) best_named = &e;
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
  }
  return d;
}

}  // namespace shard::measure
