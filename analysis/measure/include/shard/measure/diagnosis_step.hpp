#pragma once
// One step of the single-set diagnosis (set_diagnosis.hpp): the model so far (base parameters and the
// effects kept by earlier steps, each at a value), linearised around itself, every run scored
// against one frozen simulated band.
//
// Step k's nuisance parameters are the base parameters (relative +5 % steps) and the kept effects
// (+1/4 of a trial size, or -1/4 at the top of the range): the candidates' score test and refits
// profile them out, so a second effect is judged on what the first leaves, with the first
// re-sized along.
#include <algorithm>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shard/measure/diagnosis.hpp"
#include "shard/measure/effect_library.hpp"
#include "shard/measure/rate_comparison.hpp"

namespace shard::measure {

// Where a linearised refit may take the model: base parameters within 0.55..1.9 x their start,
// an effect within 0.05..3.9 plausible sizes from neutral (inside calibrate_effect's BOBYQA
// bounds 0.5..2 and -4..4). A long linear step can reach a stiffness whose run is unstable; the
// diagnosis's refit and the calibration's start use the same clamps so that the start is cached.
// An effect whose physical range reaches both sides of neutral (the supports' friction: less or
// more than the reference's) keeps the side the data ask for; any other stays on its trial's side.
inline double clamp_base_factor(double factor) { return std::clamp(factor, 0.55, 1.9); }
inline double clamp_effect_scale(const CandidateEffect& effect, double scale) {
  const bool other_side = scale < 0 && effect.scale_min() < 0;
  return other_side ? -std::clamp(-scale, 0.05, 3.9) : std::clamp(scale, 0.05, 3.9);
}

// How a model's runs are scored against the data (--scoring):
//   Own         chi^2 with the model's own band; scattering more is stopped by the NRMSE rule
//               (confirmation.hpp: a refit whose NRMSE rises is neither named nor kept);
//   FrozenBand  chi^2 with the reference model's simulated band (with_simulated_band);
//   Likelihood  chi^2 with its own band plus the variance term of the Gaussian likelihood,
//               sum ln(v / v_ref) (log_variance_ratio).
// Own is the default: with three packing seeds the simulated variances are estimated to ~100 %,
// the likelihood's log term is then noise of order 1 per component (it named support friction for
// a seating toe and Weibull strength for hidden support friction), and the frozen band charges a
// model's genuine extra scatter as error (it lost the hidden softening). docs/explanation/diagnosis.md.
enum class Scoring { Own, FrozenBand, Likelihood };
Scoring scoring_from_name(const std::string& name);  // "own", "frozen" or "likelihood"; throws otherwise

struct StepModel {
  std::vector<double> parameters;  // values of the base parameters (keys)
  std::vector<std::pair<const CandidateEffect*, double>> kept;  // effect, value
};
// "base + bond_softening (0.41)": the model a step stands on, as reports and logs name it.
std::string model_name(const StepModel& m);

ModelPlan step_plan(const ModelPlan& scene, const std::vector<std::string>& keys, const StepModel& model);

// The model's trial-size units of a kept effect's value.
double effect_scale(const CandidateEffect& e, double value);

// `c` with every rate's simulated band replaced by `reference`'s (with_simulated_band).
RateComparison with_band(const RateComparison& c, const RateComparison& reference);
// The failure point as a component of its own: the squared score of failure_displacement (the
// pins' displacement where the force has fallen to half of F_max after the peak), summed over the
// rates. Not in the residual vector by default (the comparison grid ends at the shortest measured
// curve, so the model's failure shows there only as far as the data reach); 0 when it is judged
// already (--judge-fracture), NaN when a rate's curves lack it. ConfirmationRule: it tells apart
// refits that all leave noise on the judged components.
double failure_point_chi_square(const RateComparison& c);
// The score a decision compares (a chi^2 for the frozen band; -2 ln L up to a constant).
double model_score(const RateComparison& c, const RateComparison& reference, Scoring scoring);

struct StepLinearisation {
  ResidualVector base;
  RateComparison base_comparison;                 // own band (its NRMSE and verdict text)
  std::vector<std::vector<double>> jacobian;      // base parameters, then kept effects
  std::vector<double> kept_scale_step;            // per kept effect, the trial sizes stepped
  std::vector<EffectSignature> signatures;  // candidates, as `candidates`
};

// `band`: the reference band; empty: the step's base comparison is the reference (the first
// step). With FrozenBand every run's residual vector is scored against it; otherwise each keeps
// its own band (the Jacobian and signatures are differences of standardised residuals).
StepLinearisation linearise_step(Simulator& simulator, const MeasuredRates& data, const ModelPlan& scene,
                                 const std::vector<std::string>& keys, const StepModel& model,
                                 const std::vector<const CandidateEffect*>& candidates, const RateComparison* band,
                                 Scoring scoring, std::ostream& log);

// The effects with their plausible_from rules resolved on the base run (effect_scaling.hpp): the
// model `base` at every rate of the data, on the command's packing seeds, recorded as the lab
// recorded (the linearisation's first run, so it is simulated once). The scales are the model's,
// not the measured curves': a hidden compliance, a seating toe, a preload or the lab's noise do
// not move the probe, and the tiny beam at its scene values gets the sizes its tests were tuned
// with. `described` receives one line per resolved effect (empty when none has a rule).
std::vector<CandidateEffect> plausible_on_base_run(std::vector<CandidateEffect> effects, Simulator& simulator,
                                                   const MeasuredRates& data, const ModelPlan& base,
                                                   std::string& described, std::ostream& log);

// Where a linearised refit takes a step's model: base factors and effect sizes clamped as
// clamp_base_factor / clamp_effect_scale and the effect's physical range; `at_bound` lists what
// was clamped, e.g. "bond.youngs_modulus at 1.9 x (asked 2.4 x)".
struct RefitPlan {
  StepModel model;
  std::vector<std::string> at_bound;
  bool base_at_bound = false;  // a base parameter (not an effect) was clamped
};
// lr: base steps (relative) then kept effects' steps (trial sizes), as the step's Jacobian.
RefitPlan refit_plan(const std::vector<std::string>& keys, const StepModel& start, const LinearRefit& lr,
                     const CandidateEffect* added);

// The step a refit's model took from the step's start, in the linearisation's units: relative
// changes of the base parameters, then trial sizes of the kept effects, then (with `added`) the
// added effect's trial sizes from neutral.
std::vector<double> refit_step(const std::vector<std::string>& keys, const StepModel& start, const StepModel& refit,
                               const CandidateEffect* added);

// One secant iteration of a refit (Broyden's rank-one update): the linearisation [J | s] is
// corrected along the step `step` so that it reproduces the refit's simulated residual
// `simulated` there, and the least-squares refit from the step's residual r0 is solved again. An
// effect's response is not linear in its size (a softening ratio 2.4 trial sizes from neutral
// bends the curve less than 2.4 times the trial does), so the first linear refit of a
// several-effect model can stop short, and the kept effect's size with it. nullopt when the step
// is empty or the simulated components differ from the linearisation's.
std::optional<LinearRefit> secant_refit(const ResidualVector& r0,
                                                 const std::vector<std::vector<double>>& jacobian,
                                                 const EffectSignature* added, const std::vector<double>& step,
                                                 const ResidualVector& simulated);

}  // namespace shard::measure
