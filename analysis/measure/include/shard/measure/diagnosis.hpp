#pragma once
// The statistics of `shard diagnose`, on standardised residual vectors r (Comparison::
// residual_vector: regime mean residuals and feature scores, each ~ N(0, 1) when the model is
// right).
//
// Linearised model around the calibrated base:  r(theta, a) = r0 + J dtheta + a s,
//   J  (m x p) the base-parameter Jacobian by finite differences,
//   s  the effect's signature: r(effect on at its trial size) - r(base), on the same packing
//      seeds (common random numbers) so that packing noise cancels in the difference,
//   a  the effect size in units of the trial size.
// What the existing parameters can absorb is removed by projecting onto the orthogonal
// complement of J: P = I - J (J^T J)^-1 J^T, y = P r0, t = P s. The score (Lagrange multiplier)
// statistic for a = 0 with theta profiled out is
//   LM = (t . y)^2 / (t . t)  ~ chi-square(1) under "the effect is absent",
// and the least-squares size a* = -(t . y) / (t . t) (the effect must cancel the residual).
// Refitting that one effect lowers chi^2 = |y|^2 by exactly LM; AIC = chi^2 + 2k and BIC =
// chi^2 + k ln m compare the base model (k = p) with base + effect (k = p + 1).
#include <limits>
#include <string>
#include <vector>

namespace shard::measure {

struct EffectSignature {
  std::string name;
  double trial_size = 0;          // the effect parameter value used for the signature
  std::vector<double> signature;  // s, same components as the residual
  // The physically admissible multiples a of the trial (size a * trial_size from neutral): a
  // compliance, a viscosity or a Weibull modulus cannot go below neutral, so a = [0, inf).
  double scale_min = -std::numeric_limits<double>::infinity();
  double scale_max = std::numeric_limits<double>::infinity();
  // False for a rate effect on data of fewer loading rates than it needs (CandidateEffect::
  // rates_needed): scored and ranked, never the verdict.
  bool identifiable = true;
  // Each packing seed's signature alone (seed s's effect run minus seed s's base run), the same
  // components; they average to `signature`. Empty with one seed.
  std::vector<std::vector<double>> seed_signatures{};
};

struct EffectScore {
  std::string name;
  double score = 0;           // LM statistic
  double p_value = 1;         // chi-square(1)
  double explained = 0;       // LM / |y|^2: share of the unabsorbed weighted residual it explains
  double size = 0;            // estimated effect parameter value, a* trial_size
  bool at_bound = false;      // the data ask for more than the admissible range (size clamped there)
  double chi_square_after = 0;
  double absorbed = 0;        // share of |s|^2 the base parameters absorb (1 - |t|^2 / |s|^2)
  double delta_aic = 0;       // AIC(with effect) - AIC(base) = -LM + 2
  double delta_bic = 0;
  std::vector<std::string> explains;  // residual components it reduces the most
  bool identifiable = true;           // EffectSignature::identifiable
  // How often the packing seeds' scatter alone would move the residual towards zero as far as
  // the fitted size does on their mean (one-sided t over the seeds' moves a* s_k . (-y)); 0 when
  // not tested (one seed). An effect not `resolved` is ranked but does not decide the verdict:
  // its signature may be no larger than the model's own packing scatter.
  double seed_p = 0;
  bool resolved = true;
};

struct Diagnosis {
  double chi_square = 0;            // |r0|^2
  double chi_square_unabsorbed = 0; // |y|^2 after the base parameters
  double p_value = 1;               // of |y|^2 against chi-square(m - p)
  std::vector<EffectScore> ranking; // best first
  // Pairs whose absorbed-out signatures are nearly parallel (|cos| > collinear_cosine).
  std::vector<std::pair<std::string, std::string>> indistinguishable;
  std::string verdict;  // "adequate", "<effect>", or "unexplained structured residual"
};

struct DiagnoseOptions {
  double adequate_p = 0.05;        // residual compatible with noise above this p-value
  double significant_p = 0.01;     // an effect counts below this p-value over the candidates ...
  double min_explained = 0.5;      // ... and only if it explains at least this share
  double collinear_cosine = 0.95;
  double seed_p = 0.05;  // resolved below this seed_p (ConfirmationRule::seed_p)
};

Diagnosis diagnose(const std::vector<std::string>& component_names, const std::vector<double>& residual,
                   const std::vector<std::vector<double>>& base_jacobian_columns,
                   const std::vector<EffectSignature>& effects, const DiagnoseOptions& options = {});

}  // namespace shard::measure

namespace shard::measure {

// The linearised joint refit of the base parameters and some effects: minimises
// |r0 + J dtheta + S a|^2 by least squares. dtheta is in the Jacobian's units (relative steps),
// a in units of each effect's trial size; chi_square is the predicted minimum.
struct LinearRefit {
  std::vector<double> base_step;
  std::vector<double> effect_scale;
  double chi_square = 0;
};

LinearRefit linear_refit(const std::vector<double>& residual, const std::vector<std::vector<double>>& base_jacobian_columns,
                         const std::vector<EffectSignature>& effects);

}  // namespace shard::measure
