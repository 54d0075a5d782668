#pragma once
// The single-set diagnosis (`shard diagnose` without --reference): which candidate effects
// explain what the calibrated base model misses in one measurement set.
// 1. One batch on the model's packing seeds (common random numbers): the base, each base
//    parameter +5 % (the Jacobian), each library effect at its plausible size (signature).
//    A model cannot win by scattering more: a refit whose NRMSE rises is neither named nor kept
//    (Scoring::FrozenBand / Likelihood: other scorings, diagnosis_step.hpp).
// 2. Score test on the part of the residual the base parameters cannot absorb (diagnosis.hpp).
// 3. Confirmation: the base refit alone and the top effects refit with it (linear prediction of
//    the sizes) are simulated; the real drop in chi-square and the information criteria decide
//    (confirmation.hpp).
// 4. Stepwise: a refit that explains most of the excess but leaves structure is kept, and steps
//    1-3 run again around the model with it (diagnosis_step.hpp), up to max_effects effects.
// Everything runs through a Simulator; the renderers (markdown, JSON) read the result.
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "shard/measure/confirmation.hpp"
#include "shard/measure/diagnosis_step.hpp"

namespace shard::measure {

// A secant iteration that lowers a refit's chi^2 by less than this has converged: a quarter of
// the rival margin (ConfirmationRule::rival_chi_square, 2), below what the decision resolves.
inline constexpr double kConvergedChiSquare = 0.5;

struct SetDiagnosisOptions {
  std::vector<std::string> params;  // calibrated base parameters section.key (values read from the scene)
  // Effects confirmed by a refit run per step (0: the score test decides). Three: on the tiny beam
  // with hidden softening, the supports' friction and the compression asymmetry outrank the
  // softening in the score test and only a refit tells them apart.
  int refit = 3;
  int max_effects = 2;              // effects the stepwise diagnosis may add one after the other
  int refit_iterations = 4;         // secant iterations of a kept effect's refit and of later steps' refits
  Scoring scoring = Scoring::Own;
};

// One simulated refit of a step: the base refit (no effect) or the step's model with one effect.
struct RefitRun {
  std::string name;  // "base refit" or the effect
  RefitPlan plan;
  const CandidateEffect* effect = nullptr;  // the effect added (none for the base refit)
  // Its signature in the step's linearisation: read during the step only.
  const EffectSignature* signature = nullptr;
  int secant_steps = 0;  // secant iterations that improved on the linear refit
  double effect_value = 0;
  double chi_square = 0, nrmse = 0, delta_aic = 0, delta_bic = 0;
  double noise_nrmse = std::numeric_limits<double>::quiet_NaN();  // RateComparison::noise_nrmse
  // The failure point's score (failure_displacement, every rate), NaN when a curve lacks it.
  double failure_chi_square = std::numeric_limits<double>::quiet_NaN();
  ResidualVector residual;  // as scored (the decision's components)
  std::vector<ResidualVector> seed_residuals;  // each packing seed's alone, in residual's units
  std::string failure;      // the refit's run failed: its first error line
};

// Everything one step computed.
struct DiagnosisStepRecord {
  StepModel model;  // the step's starting model
  std::vector<const CandidateEffect*> candidates;
  StepLinearisation lin;
  Diagnosis diagnosis;
  std::vector<RefitRun> refits;  // the base refit first
  ConfirmationDecision decision;
  // The kept effect's refit carried by secant iterations towards its minimum (the next step's model).
  std::optional<RefitRun> kept_converged;
  // The decision's entry for refits[k] (none for the base refit, k = 0).
  const ConfirmedEffect* confirmed(std::size_t k) const {
    return k > 0 && k - 1 < decision.effects.size() ? &decision.effects[k - 1] : nullptr;
  }
};

// The result holds pointers into its own `effects`: it moves, it does not copy.
struct SetDiagnosisResult {
  SetDiagnosisResult() = default;
  SetDiagnosisResult(SetDiagnosisResult&&) = default;
  SetDiagnosisResult& operator=(SetDiagnosisResult&&) = default;
  SetDiagnosisResult(const SetDiagnosisResult&) = delete;
  SetDiagnosisResult& operator=(const SetDiagnosisResult&) = delete;

  std::vector<std::string> keys;         // the base parameters
  std::vector<CandidateEffect> effects;  // with their plausible sizes resolved on the base run
  std::string scaled_sizes;              // plausible_on_base_run's lines (empty: no rule)
  std::vector<DiagnosisStepRecord> steps;
  std::vector<DiagnosisStep> path;       // the effects added, one per step
  StepModel model;                       // the path's model (the start when the path is empty)
  std::string verdict;                   // an effect, "a + b", kAdequate or kUnexplained
  // p of a later step's base refit within noise: the kept effect re-sized around itself fits, but
  // its own refit did not reach noise, so it is not named. Empty otherwise.
  std::optional<double> resized_p;
  bool base_out_of_range = false;  // a base refit reached its bound
  std::string unidentifiable;      // the first step's rate effect that would have been named
  RunHealth health;

  const CandidateEffect* effect(const std::string& name) const;
};

// Throws std::invalid_argument when `library` is empty.
SetDiagnosisResult diagnose_set(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene,
                                std::vector<CandidateEffect> library, const SetDiagnosisOptions& options,
                                std::ostream& log);

}  // namespace shard::measure
