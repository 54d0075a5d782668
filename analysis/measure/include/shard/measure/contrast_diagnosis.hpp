#pragma once
// The contrast diagnosis (docs/explanation/diagnosis.md "Lab data: contrasts across sets"): which library effect makes each
// measurement set differ from the reference (or from the consensus of the others), with the base
// model's form error cancelled in the difference. Steps:
// 1. the base parameters fitted to the reference on simulated runs; its form error reported;
// 2. one batch on common packing seeds: the base and each effect at its plausible size, at every
//    rate the sets were tested at; each set's measured contrast against the effects' simulated
//    contrasts (linear sizes, Hotelling's test for "no difference");
// 3. confirmation: the best effects of each set simulated at their fitted sizes (and once more at
//    the size their simulated contrast asks for); those runs decide;
// 4. two effects at once: where the closest single effect leaves a remainder beyond noise, it is
//    kept and the next sought as a pair with it.
// The statistics are contrast.hpp; the study (sets, base fit, simulated contrasts) is
// contrast_study.hpp; everything runs through a Simulator.
#include <algorithm>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "shard/measure/contrast_study.hpp"
#include "shard/measure/effect_library.hpp"
#include "shard/measure/fracture_validity.hpp"

namespace shard::measure {

// The library's plausible_from rules resolved from the scene's fitted base run
// (shard/measure/effect_scaling.hpp); simulates the base once when an effect has a rule (the
// study's next batch then finds those runs in the cache). The sizes are logged and kept in
// `described` for the report.
std::vector<CandidateEffect> scaled_to_base_run(std::vector<CandidateEffect> effects,
                                                         ContrastStudy& study, std::string& described,
                                                         std::ostream& log);

// The fitted base's run; throws, naming the base model, when it gives no usable curve (a base
// that does not bend up to a fracture at one of the study's rates leaves nothing to contrast).
ContrastStudy::Simulated simulate_base(ContrastStudy& study, std::ostream& log);

// The farthest an effect is sized from neutral where the data choose the size freely (calibrate's
// search, a pair's second effect), in trial steps (its library size): a size the library's
// plausible value misjudges by more is a different effect.
inline constexpr double kFarthestTrialSteps = 8.0;

// An effect's sizes, in trial steps, where the data choose them freely: its physical range within
// kFarthestTrialSteps of neutral.
inline double lowest_free_size(const CandidateEffect& e) { return std::max(e.scale_min(), -kFarthestTrialSteps); }
inline double highest_free_size(const CandidateEffect& e) { return std::min(e.scale_max(), kFarthestTrialSteps); }

// One base assumption moved (roller friction, damping, self-weight, ...): the shown model rerun
// on the moved base, its simulated contrast against the measured one.
struct AssumptionSensitivity {
  std::string assumption;  // "section.key=value", the moved condition
  // The effect size the measured contrast asks for on the moved base, per the size it asks for on
  // the base (linear projection on the model's contrast): 1 when the verdict does not lean on it.
  double size_ratio = 1;
  ContrastStudy::CurveContrast after;  // the shown model's contrast curve on the moved base
  bool curve_agrees = false;           // within curve_floor_factor x naming_floor, as a name needs
};

// The rule that withheld a set's name (SetDiagnosis::withheld).
enum class WithheldBy {
  curve,        // its curve or its share of T^2 does not bear it out (require_curve_agreement)
  rate,         // its rates cannot resolve its strength's rate dependence, or show one (require_resolved_rate_dependence)
  own_scatter,  // the set carries its own scatter (withhold_names_of_own_scatter)
  fractures,    // half its specimens or more broke outside the inner span (withhold_names_of_invalid_fractures)
  base,         // the fitted base does not reproduce the reference (withhold_names_on_a_distant_base)
};

struct SetDiagnosis {
  std::size_t set = 0;
  ContrastStudy::Contrast contrast;
  ContrastDecision linear;    // from the signatures at the plausible sizes
  ContrastDecision decision;  // from the confirmation runs (the linear one when none ran)
  std::vector<double> confirmed_values;  // effect values of decision.fits' runs, by fit name order
  ContrastStudy::CurveContrast before, after;  // base model; with the named (or best) effect
  std::string after_effect;
  double after_value = 0;
  std::vector<double> after_components;  // the shown effect's simulated contrast, per component
  // The confirmed run of decision.fits.front() (the closest single effect), which a pair starts from.
  struct ConfirmedRun {
    std::size_t effect = 0;  // index into the library
    double scale = 0;        // in trial sizes from neutral
    ContrastStudy::Simulated run;
  };
  std::optional<ConfirmedRun> closest;
  // Two effects at once (contrast_pairs.cpp): the best pair simulated, named or not, and its values.
  std::optional<ContrastPairFit> pair;
  double pair_values[2] = {0, 0};
  std::size_t seconds_tried = 0;
  // The share of T^2 the verdict explains (for an unexplained difference: the closest effect's or
  // pair's), and the name the statistics gave but a rule withheld (empty otherwise).
  double share = 0;
  std::string withheld;
  // Named by its curve (name_by_curve): the components beyond the rising branch differ beyond noise.
  bool named_by_curve = false;
  // The rule that withheld `withheld`.
  WithheldBy withheld_by = WithheldBy::curve;
  // The set's rate dependence of its strength, when it was tested at two or more rates
  // (require_resolved_rate_dependence).
  std::optional<RateSensitivity> rate_sensitivity;
  // How the shown model (named, or the closest) fares when a condition the base assumes is moved
  // (ContrastDiagnosisOptions::assumptions), one per assumption.
  std::vector<AssumptionSensitivity> assumptions;
  // Its specimens that gave no bending strength (broke outside the pins, or did not break apart).
  FractureValidity fractures;
};

// The base model, at the reference's reported grain size when `lab_grain_size` (throws, naming the
// metadata file, when the reference reports none).
ModelPlan base_at_grain_size(const ContrastSets& sets, const Simulator& simulator, const ModelPlan& base,
                             bool lab_grain_size, std::ostream& log);

// The set is named as a pair of effects (the pair rule named it and the curve bore it out).
bool names_a_pair(const SetDiagnosis& d, const ContrastOptions& options = {});

// The noise floor a named model's rising-branch contrast is held to: the curve's own floor with
// the form tolerance of the model's contrast added (ContrastOptions::form_tolerance, as the
// component test adds it): the library's effect and the lab's are the same physics in two forms.
double naming_floor(const ContrastStudy::CurveContrast& c, const ContrastOptions& options = {});

// The curve rule: the contrast's rising branch within curve_floor_factor x naming_floor.
bool curve_agrees(const ContrastStudy::CurveContrast& c, const ContrastOptions& options = {});

// The shown model's contrast curve fits the measured one better than the base's over the whole
// curve (NRMSE after < before). An effect that leaves the contrast curve worse than no effect at
// all does not explain the set, however well it fits the components: on the foreign sets a
// roller-friction batch fitted bond_softening (85 % of T^2, rising branch within its floor) while
// its contrast NRMSE rose from 2.9 % to 4.7 %; every right name lowered it.
bool improves_on_base(const SetDiagnosis& d);

// What a name asks of a model's contrast curve (`after`, against the base's `before`): its rising
// branch within the floor (curve_agrees) and the whole curve fitted better than by the base.
bool curve_bears_out(const ContrastStudy::CurveContrast& after, const ContrastStudy::CurveContrast& before,
                     const ContrastOptions& options);

// The last word on a name (ContrastOptions::curve_floor_factor, min_share): a set named by the
// component statistics whose named model does not reproduce the contrast curve to within its
// noise floor, does not improve on the base's contrast curve, or explains less than min_share of
// T^2, becomes an unexplained difference.
void require_curve_agreement(std::vector<SetDiagnosis>& sets, const ContrastOptions& options);

// The marginal standard uncertainty of each component of the measured contrast (its weight is
// the inverse covariance).
std::vector<double> component_uncertainties(const ContrastStudy::Contrast& c);

// A peak-force component of a contrast (ln_peak_force, or ln_peak_force@rate of one rate group).
bool is_peak_force_component(const std::string& name);

// A component of the rising branch (ln_stiffness, nonlinearity, or either @rate).
bool is_rising_branch_component(const std::string& name);

// How many standard uncertainties a name by its curve may leave between a model's component and the
// measured one: curve_name_peak_sigmas for the peak force, curve_name_rising_sigmas for the rising
// branch's; infinite for the components that carry the fracture's form.
double curve_name_sigmas(const std::string& component, const ContrastOptions& options = {});

// The first of a model's contrast components (`model`, as ContrastStudy::model_contrast orders
// them) that lies beyond curve_name_sigmas of the measured one, the uncertainty widened by the form
// tolerance of the model's own change; none when the model reproduces them all.
std::optional<std::size_t> component_missed_by_curve_name(const ContrastStudy::Contrast& c,
                                                          const std::vector<double>& model,
                                                          const ContrastOptions& options = {});

// The other way round: a set left unexplained (no pair named) whose closest single effect has a
// significant drop over the `tried` effects, explains at least curve_name_share of T^2,
// reproduces the contrast curve within the curve rule and leaves no component missed
// (component_missed_by_curve_name) is named by it (named_by_curve), with the rivals the component
// rule would list.
void name_by_curve(std::vector<SetDiagnosis>& sets, std::size_t tried, const ContrastOptions& options);

// The order of the naming rules after the confirmations: the curve rule withholds the single
// names it does not bear out (one may be half of a pair), then a set its closest effect explains
// by the curve is named by it, then `seek_pairs` (none: no pair search) completes the sets still
// unexplained to pairs, which the curve rule judges again. One cause before two: a pair sought before the curve name would
// fit a second effect to the fracture's form that the curve rule leaves to the first.
void name_sets(std::vector<SetDiagnosis>& sets, std::size_t tried, const ContrastOptions& options,
               const std::function<void(std::vector<SetDiagnosis>&)>& seek_pairs);

// A set tested at several rates whose verdict names only rate-independent effects (no rate
// effect, CandidateEffect::rates_needed 1) for a strength difference (rate_sensitivity.hpp): the
// name stands only when the set resolves its rate dependence and shows none (the 95 % interval of
// its change holds zero: a rate-independent cause gives the same change at every rate); otherwise
// the set reads
// "unexplained difference" with the name as its closest. Fills every multi-rate set's
// rate_sensitivity for the report.
void require_resolved_rate_dependence(std::vector<SetDiagnosis>& sets, const ContrastStudy& study,
                                      const ContrastStudy::Simulated& base,
                                      const std::vector<CandidateEffect>& effects, const ContrastOptions& options);

// A set that carries its own scatter (GroupScatter::own) is not named: its verdict reads
// "unexplained difference" with the name as its closest. Its covariance takes, component by
// component, the larger of its own standard deviation and the pool's, the first from n - 1 = 3
// degrees of freedom for four specimens, yet its tests refer it to the pool's: the widened
// covariance lets a remainder pass as noise that the pool would reject. On the default-size
// foreign study a frictionless-roller set, whose beams slid off their supports in 2-3 of 4
// specimens, was named weibull_strength that way. A scatter that wide is a difference of its
// own, which no shift of the mean describes.
void withhold_names_of_own_scatter(std::vector<SetDiagnosis>& sets, const ContrastStudy& study);

// Each set's fractures judged (fracture_validity.hpp); a set of which half or more gave no bending
// strength is not named: its verdict reads "unexplained difference" with the name as its closest.
// On the default-size foreign study a batch on frictionless rollers and pins slid off its supports
// in 3 of 4 specimens (no bond broke); its force maximum was the slide's, and a name drawn from it
// would send the lab after material physics for a fixture fault.
void withhold_names_of_invalid_fractures(std::vector<SetDiagnosis>& sets, const ContrastSets& measured);

// No set is named when the fitted base leaves more than ContrastOptions::base_nrmse_limit of form
// error against the reference: the contrasts are the effects' moves about the base, and about a
// base that is not the reference's specimen (a fit that did not converge, a model that crushes at
// its rollers) they move otherwise than about the lab's. Each name reads "unexplained
// difference" with the name as its closest.
void withhold_names_on_a_distant_base(std::vector<SetDiagnosis>& sets, double base_nrmse,
                                      const ContrastOptions& options);

// The names a verdict gives: the pair's two, the single effect, or none.
std::vector<std::string> named_effects(const SetDiagnosis& d, const ContrastOptions& options = {});

// One batch of models; when a run fails (a size the plugin refuses, an unstable one, a curve with
// no rise) the models are run one by one (finished runs are cached) and a failed one is left out
// (empty) with its reason in the log, named by `label` after the `command` that asked for it, and
// in `failures` when given (one entry per model, empty for a run that stands).
std::vector<std::optional<ContrastStudy::Simulated>> simulate_each(ContrastStudy& study,
                                                                   const std::vector<ModelPlan>& models,
                                                                   const std::function<std::string(std::size_t)>& label,
                                                                   std::ostream& log,
                                                                   const std::string& command = "diagnose",
                                                                   std::vector<std::string>* failures = nullptr);

// Simulates each set's best `count` effects at their linear sizes, then (up to `iterations` in
// all) at the size the secant through the effect's last two runs asks for; then, for a set whose
// closest effect takes most of its difference but leaves a remainder beyond noise, up to `probes`
// rounds of runs a factor sqrt(2) either side of that effect's best size. The decision is taken
// on each effect's best-fitting run.
void confirm_contrasts(ContrastStudy& study, const std::vector<CandidateEffect>& effects,
                       const ContrastStudy::Simulated& base, std::vector<SetDiagnosis>& sets, int count, int iterations,
                       int probes, ContrastOptions decide, std::ostream& log);

// Sets whose closest single effect takes a significant share of the difference but leaves a
// remainder beyond noise: that effect kept at its confirmed size, each other library effect added
// (two-column fit on the simulated contrasts), the best `count` pairs simulated with both effects
// on, re-sized once by a Gauss-Newton step when `iterations` > 1; "A + B" when the second's drop
// is significant over the seconds tried and the remainder is noise.
// `trials`: the library's runs at their plausible sizes (index e + 1; 0 is the base), and at
// index mirror[e] (0: none) effect e's run one trial step the other way, for effects that move
// both ways from the reference.
void confirm_contrast_pairs(ContrastStudy& study,
                            const std::vector<CandidateEffect>& effects,
                            const std::vector<ContrastStudy::Simulated>& trials, const std::vector<std::size_t>& mirror,
                            std::vector<SetDiagnosis>& sets,
                            int count, int iterations, ContrastOptions decide, std::ostream& log);

// Throws, naming the assumption, when the scene does not take one (a misspelt key): before any run.
void check_assumptions_apply(Simulator& simulator, const ModelPlan& base, const SceneOverrides& assumptions);

// Each assumption moved on the fitted base: every set's shown model (the named effect or pair, or
// the closest) rerun there at its confirmed size, and its contrast held against the measured one.
void assess_assumptions(ContrastStudy& study, const std::vector<CandidateEffect>& effects,
                        std::vector<SetDiagnosis>& sets, const SceneOverrides& assumptions,
                        const ContrastOptions& decide, std::ostream& log);

// What the diagnosis is asked to do beyond the decision rules (`decide`).
struct ContrastDiagnosisOptions {
  std::vector<std::string> params;  // base parameters section.key fitted to the reference
  int base_iterations = 3;          // Gauss-Newton iterations of the base fit
  int confirm = 2;                  // best effects per set confirmed by simulated runs
  int confirm_iterations = 4;
  int confirm_probes = 2;           // rounds of size probes beyond the secant (0: none)
  int pairs = 2;                    // pairs simulated per set (0: single effects only)
  int pair_iterations = 3;
  double finer = 0;                 // > 0: the base also fitted at diameters this factor smaller
  bool lab_grain_size = false;      // the model at the reference's [test] grain_size
  // Conditions the base assumes, each moved in turn to report how much every verdict leans on it
  // (one base run and one run of each set's shown model per assumption).
  SceneOverrides assumptions;
  ContrastOptions decide;
};

// Everything the diagnosis found, for the renderers (markdown, JSON, plot) and for tests.
struct ContrastDiagnosis {
  std::vector<CandidateEffect> effects;  // with their plausible sizes resolved on the base run
  std::string scaled_sizes;              // scaled_to_base_run's lines
  BaseCalibration calibration;
  std::optional<BaseCalibration> finer;  // the base fitted at a finer packing, when asked for
  double finer_factor = 0;
  double dof = 0;                         // of the pooled specimen covariance
  // Each (set, rate) group's scatter against the others' (group_scatter.hpp), the reference's too.
  struct GroupScatterLine {
    std::size_t set = 0;
    double rate = 0;     // m/s
    double ratio = 1;    // its widest component's variance over the others' pooled variance
    std::string component;  // that component's name
    double p_value = 1;  // of that ratio under one common scatter
    bool own = false;    // set apart: its contrast uses its own scatter
  };
  std::vector<GroupScatterLine> scatter;
  std::vector<double> rates;              // every rate simulated
  // Library effects whose trial (on either side) gave no usable run, with the reason: their
  // contrasts cannot be read, so no set is held against them.
  struct LeftOutEffect {
    std::string name, reason;
  };
  std::vector<LeftOutEffect> left_out;
  std::vector<SetDiagnosis> sets;         // one per set held against the reference
  FractureValidity reference_fractures;   // the reference's specimens judged alike
  RunHealth health;
};

ContrastDiagnosis diagnose_contrasts(const ContrastSets& sets, Simulator& simulator, const ModelPlan& base,
                                     const std::vector<CandidateEffect>& library,
                                     const ContrastDiagnosisOptions& options, std::ostream& log);

}  // namespace shard::measure
