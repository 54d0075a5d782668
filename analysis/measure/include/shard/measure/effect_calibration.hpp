#pragma once
// The single-set calibration (`shard calibrate-effect`): one library effect added to the model
// and its parameter fitted together with chosen base parameters to one measurement set (NLopt
// BOBYQA, derivative-free: each objective value is a set of simulations). Objective: chi^2 of the
// standardised residual vector (regime means and feature scores), on fixed packing seeds so that
// it is a deterministic function. Start: the linearised refit, the first step of diagnose_set on
// the same runs (cached by a caching simulator). Every evaluation is scored against the base
// model's simulated band where the scoring asks for it; the result says how much of the gain the
// base parameters made without the effect (GainCredit).
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "shard/measure/confirmation.hpp"
#include "shard/measure/diagnosis_step.hpp"

namespace shard::measure {

struct EffectCalibrationOptions {
  std::vector<std::string> params;  // base parameters section.key fitted along (values read from the scene)
  int max_evaluations = 16;         // objective evaluations (each one run per packing seed)
  Scoring scoring = Scoring::Own;
};

// Which end of its range a fitted coordinate reached.
enum class RangeEnd { None, Lower, Upper };

struct EffectCalibration {
  std::optional<CandidateEffect> effect;  // with its plausible size resolved on the base run; none: base refit
  std::vector<std::string> keys;          // the base parameters
  std::vector<double> start;              // their values in the scene
  // The fit's coordinates: base parameters relative to their start, then the effect in plausible
  // sizes from neutral; with the range searched.
  std::vector<double> best, lower, upper;
  int evaluations = 0;
  std::string stop;  // why the optimiser stopped
  RateComparison before, after;
  std::optional<RateComparison> base_only;  // the fitted base parameters with the effect at neutral
  double chi_square_before = 0, chi_square_after = 0;  // as scored (Scoring)
  std::optional<double> chi_square_base_only;
  GainCredit credit;
  RunHealth health;

  double fitted(std::size_t i) const { return start[i] * best[i]; }  // base parameter i's value
  double effect_value() const { return effect ? effect->value_at(best.back()) : 0.0; }
  RangeEnd base_at_bound(std::size_t i) const;
  RangeEnd effect_at_bound() const;
};

// `effect`: the library effect added (its plausible_from rule resolved here); none: the base
// parameters are refitted alone. Throws std::invalid_argument when there is nothing to fit.
EffectCalibration calibrate_effect(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene,
                                   std::optional<CandidateEffect> effect, const EffectCalibrationOptions& options,
                                   std::ostream& log);

}  // namespace shard::measure
