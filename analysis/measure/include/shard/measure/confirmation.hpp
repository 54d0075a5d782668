#pragma once
// The decision of `shard diagnose` once the refits have been simulated (issue 7): which effect,
// if any, is named. The score test (diagnosis.hpp) ranks on a linearisation; the refit runs are
// the real model, so they decide. With m residual components, p base parameters and chi^2_0 the
// base refit's chi-square:
//   structured excess   E = chi^2_0 - (m - p), what noise alone does not explain (the expected
//                       chi^2 of a right model is its degrees of freedom);
//   share explained     (chi^2_0 - chi^2_e) / E by the refit with effect e;
//   information         dAIC = chi^2_e - chi^2_0 + 2, dBIC = chi^2_e - chi^2_0 + ln m (one extra
//                       parameter);
//   what remains        p_after = P(chi^2(m - p - 1) > chi^2_e);
//   the drop itself     p_drop = P(chi^2(1) > chi^2_0 - chi^2_e), the likelihood-ratio test of
//                       the nested models.
// An effect is named when it explains at least `min_explained` of the excess, both criteria
// prefer it (dAIC < 0 and dBIC < 0), its drop is significant (p_drop below `drop_p` = 0.05
// shared by the refits tried, Bonferroni: trying more candidates must not make a chance
// improvement a name) and what remains is compatible with noise at the level the null case is
// judged by (p_after > `remaining_p` = 0.05, DiagnoseOptions::adequate_p): the name means "the
// base model plus this effect is adequate". A refit that improves the fit without meeting all
// of these is reported as a partial explanation and the verdict is "unexplained structured
// residual": the data say something is missing, not that it is this candidate. Unless the base
// refit itself is compatible with noise (P(chi^2(m - p) > chi^2_0) > `remaining_p`): then the
// simulated model with its base parameters refitted explains the data, whatever the
// linearisation suggested, and the verdict is "adequate".
// Rivals: other refits that explain at least `min_explained` of the excess and come within
// `rival_chi_square` of the named one (2: a dAIC under 2 between two one-parameter additions,
// "substantial support" for both in Burnham & Anderson's terms). The data cannot tell them from
// the verdict, and the report says so with the measurement that would.
#include <string>
#include <vector>

namespace shard::measure {

struct RefitOutcome {
  std::string name;
  double chi_square = 0;  // simulated chi^2 of the refit with this effect
};

struct ConfirmedEffect {
  std::string name;
  double chi_square = 0, share_explained = 0, delta_aic = 0, delta_bic = 0, p_after = 0, p_drop = 1;
  bool named = false;
};

struct ConfirmationRule {
  double min_explained = 0.5;
  double remaining_p = 0.05;
  double rival_chi_square = 2.0;
  double drop_p = 0.05;
};

struct ConfirmationDecision {
  double excess = 0;                     // E
  double base_p = 0;                     // of the base refit's chi^2 against chi^2(m - p)
  std::vector<ConfirmedEffect> effects;  // in the order given
  std::string verdict;                   // the named effect, "unexplained structured residual" or "adequate"
  std::string best_partial;              // the refit that lowered chi^2 most when none is named
  std::vector<std::string> rivals;       // refits the data cannot tell from the named one
};

inline constexpr const char* kUnexplained = "unexplained structured residual";
inline constexpr const char* kAdequate = "adequate";

ConfirmationDecision decide_from_refits(double base_refit_chi_square, const std::vector<RefitOutcome>& refits,
                                        std::size_t components, std::size_t base_parameters,
                                        const ConfirmationRule& rule = {});

}  // namespace shard::measure
