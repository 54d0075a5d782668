#pragma once
// The decision of `shard diagnose` once the refits have been simulated: which effect,
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
// Scattering. A candidate's chi^2 must not fall because its replicates scatter more (a wider
// band shrinks every standardised residual): diagnose scores every run against one frozen band
// (Comparison::with_simulated_band), and a refit whose NRMSE rises above the base refit's is not
// named or kept, whatever its chi^2 did (`nrmse_may_rise` = false).
//
// Identifiability. A rate effect refit on data of one loading rate (RefitOutcome::identifiable
// false: CandidateEffect::rates_needed) is judged like the others but can be neither named nor
// kept: at one rate it changes only the curve's shape, which a rate-independent effect changes
// too (a viscosity a tenth of the time to peak fitted hidden softening and asymmetry data as well
// as the right effect did). It is a rival when it fits as well as the named one, and when it alone
// would have been named the verdict stays "unexplained structured residual" with its name in
// `unidentifiable` (the report asks for a second rate). It does not count in the Bonferroni share:
// it cannot produce a name.
//
// Several effects (stepwise). A refit that meets every rule but the last (it explains most of the
// excess, significantly, and the information criteria prefer it, but structure remains) is
// `kept`: the diagnosis adds it to the model and diagnoses the remainder with it (DiagnosisStep).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace shard::measure {

struct RefitOutcome {
  std::string name;
  double chi_square = 0;  // simulated chi^2 of the refit with this effect
  // Its NRMSE; NaN when not known (the no-rise rule is then not applied).
  double nrmse = std::numeric_limits<double>::quiet_NaN();
  bool identifiable = true;  // false: a rate effect on data of too few rates (above)
  // How often the packing seeds alone would move the residual as far its way: the one-sided
  // p of the seeds' agreement (seed_consistency_p); 0 when not tested (one seed).
  double seed_p = 0;
};

struct ConfirmedEffect {
  std::string name;
  double chi_square = 0, share_explained = 0, delta_aic = 0, delta_bic = 0, p_after = 0, p_drop = 1;
  double nrmse = std::numeric_limits<double>::quiet_NaN();
  bool nrmse_rose = false;  // its NRMSE is above the base refit's: it won chi^2 by scattering
  bool qualifies = false;   // every rule but "what remains is noise"
  bool named = false;
  bool identifiable = true;  // RefitOutcome::identifiable; when false, qualifies and named stay false
  double seed_p = 0;         // RefitOutcome::seed_p
  bool resolved = true;      // seed_p below ConfirmationRule::seed_p; when false, it qualifies for nothing
  bool would_name = false;   // not identifiable, but meets every rule a name needs
};

struct ConfirmationRule {
  double min_explained = 0.5;
  double remaining_p = 0.05;
  double rival_chi_square = 2.0;
  double drop_p = 0.05;
  // Refits tried before this decision (earlier steps of a stepwise diagnosis): the Bonferroni
  // share of drop_p counts them too.
  std::size_t earlier_refits = 0;
  bool nrmse_may_rise = false;
  // An effect whose refit improves the fit only on average over the packing seeds, not seed by
  // seed, has fitted the model's packing scatter: its signature is no larger than that scatter.
  double seed_p = 0.05;
};

struct ConfirmationDecision {
  double excess = 0;                     // E
  double base_p = 0;                     // of the base refit's chi^2 against chi^2(m - p)
  double base_nrmse = std::numeric_limits<double>::quiet_NaN();
  std::vector<ConfirmedEffect> effects;  // in the order given
  std::string verdict;                   // the named effect, "unexplained structured residual" or "adequate"
  std::string best_partial;              // the refit that lowered chi^2 most when none is named
  // When none is named: the qualifying refit with the lowest chi^2, or of those within
  // rival_chi_square of it the one with the lowest NRMSE (chi^2 does not tell them apart).
  std::string kept;
  std::vector<std::string> rivals;       // refits the data cannot tell from the named one
  std::string unidentifiable;            // with no name: an unidentifiable refit that would have been named
};

inline constexpr const char* kUnexplained = "unexplained structured residual";
inline constexpr const char* kAdequate = "adequate";

ConfirmationDecision decide_from_refits(const RefitOutcome& base_refit, const std::vector<RefitOutcome>& refits,
                                        std::size_t components, std::size_t base_parameters,
                                        const ConfirmationRule& rule = {});
// The same without NRMSEs.
ConfirmationDecision decide_from_refits(double base_refit_chi_square, const std::vector<RefitOutcome>& refits,
                                        std::size_t components, std::size_t base_parameters,
                                        const ConfirmationRule& rule = {});

// Credit for a calibration's gain: chi^2 `before` (the base model), `base_only` (the fitted base
// parameters with the effect at neutral) and `with_effect` (the fitted model). The base
// parameters made before - base_only, the effect base_only - with_effect. The effect is supported
// when its own drop beats the AIC penalty of its parameter (2) and the likelihood-ratio test,
// P(chi^2(1) > drop) < 0.05; otherwise the gain belongs to the base parameters.
struct GainCredit {
  double total = 0, by_base = 0, by_effect = 0;
  double effect_p = 1;  // P(chi^2(1) > by_effect)
  bool effect_supported = false;
};
GainCredit credit_gain(double before, double base_only, double with_effect);

// One step of a stepwise diagnosis: the effect added, its size, and the model before and after.
struct DiagnosisStep {
  std::string effect;
  double value = 0;
  double chi_square_before = 0, chi_square_after = 0;  // the step's base refit, the refit with the effect
  double nrmse_before = 0, nrmse_after = 0;
  double p_after = 0;  // of what remains, against chi^2(m - p - step)
  bool named = false;  // what remains is noise: the path ends here
};

// "a + b" for a path whose last step is named; "unexplained structured residual" otherwise (the
// kept steps are then partial explanations).
std::string stepwise_verdict(const std::vector<DiagnosisStep>& path);

}  // namespace shard::measure
