#pragma once
// The contrast commands' options, per-set outcome, confirmation runs and report
// (measure_contrast.cpp, measure_contrast_calibrate.cpp).
#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "contrast_study.hpp"
#include "shard/measure/effect_library.hpp"

namespace shard {

struct ContrastOptionsCli {
  std::vector<std::filesystem::path> sets;
  std::string reference;
  std::filesystem::path library, out;
  ModelPlan model;
  SimulationOptions sim;
  std::vector<std::string> params;
  std::vector<std::string> only;
  int base_iterations = 3;
  int confirm = 2;
  int confirm_iterations = 2;
  int pair_iterations = 3;
  int pairs = 2;  // pairs of effects simulated per set whose closest single effect leaves a remainder (0: none)
  measure::ContrastOptions decide;  // --form-tolerance
  double finer = 0;  // > 0: the base also fitted at diameters this factor smaller (form error vs resolution)
};

void add_contrast_options(CLI::App* cmd, ContrastOptionsCli& o);
// The library (--effects, or effects.toml beside the scene) and its --only selection.
std::vector<measure::CandidateEffect> contrast_effects(const ContrastOptionsCli& o);
// The library's plausible_from rules resolved from the scene's fitted base run
// (shard/measure/effect_scaling.hpp); simulates the base once when an effect has a rule (the
// study's next batch then finds those runs in the cache). The sizes are logged and kept in
// `described` for the report.
std::vector<measure::CandidateEffect> scaled_to_base_run(std::vector<measure::CandidateEffect> effects,
                                                         ContrastStudy& study, std::string& described,
                                                         std::ostream& log);

// The farthest an effect is sized from neutral where the data choose the size freely (calibrate's
// search, a pair's second effect), in trial steps (its library size): a size the library's
// plausible value misjudges by more is a different effect.
inline constexpr double kFarthestTrialSteps = 8.0;

struct SetDiagnosis {
  std::size_t set = 0;
  ContrastStudy::Contrast contrast;
  measure::ContrastDecision linear;    // from the signatures at the plausible sizes
  measure::ContrastDecision decision;  // from the confirmation runs (the linear one when none ran)
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
  std::optional<measure::ContrastPairFit> pair;
  double pair_values[2] = {0, 0};
  std::size_t seconds_tried = 0;
};

// One batch of models; when a run fails (a size the plugin refuses, or an unstable one) the models
// are run one by one (finished runs are cached) and a failed one is left out (empty) with its
// reason in the log, named by `label`.
std::vector<std::optional<ContrastStudy::Simulated>> simulate_each(ContrastStudy& study,
                                                                   const std::vector<ModelPlan>& models,
                                                                   const std::function<std::string(std::size_t)>& label,
                                                                   std::ostream& log);

// Simulates each set's best `count` effects at their linear sizes, then (up to `iterations` in
// all) at the size the simulated contrast asks for; the decision is taken on those runs.
void confirm_contrasts(ContrastStudy& study, const std::vector<measure::CandidateEffect>& effects,
                       const ContrastStudy::Simulated& base, std::vector<SetDiagnosis>& sets, int count, int iterations,
                       measure::ContrastOptions decide, std::ostream& log);

// Sets whose closest single effect takes a significant share of the difference but leaves a
// remainder beyond noise: that effect kept at its confirmed size, each other library effect added
// (two-column fit on the simulated contrasts), the best `count` pairs simulated with both effects
// on, re-sized once by a Gauss-Newton step when `iterations` > 1; "A + B" when the second's drop
// is significant over the seconds tried and the remainder is noise (issue 15 item 6).
// `trials`: the library's runs at their plausible sizes (index e + 1; 0 is the base).
void confirm_contrast_pairs(ContrastStudy& study, const ContrastSets& names,
                            const std::vector<measure::CandidateEffect>& effects,
                            const std::vector<ContrastStudy::Simulated>& trials, std::vector<SetDiagnosis>& sets,
                            int count, int iterations, measure::ContrastOptions decide, std::ostream& log);

struct ContrastReport {
  const ContrastSets& sets;
  const std::vector<measure::CandidateEffect>& effects;
  const BaseCalibration& calibration;
  const ContrastStudy& study;
  const std::vector<SetDiagnosis>& diagnoses;
  double max_kinetic_to_elastic = 0;        // the base and the confirmed effects' runs
  double max_probe_kinetic_to_elastic = 0;  // the effects' trials at their library sizes
  const BaseCalibration* finer = nullptr;  // the base fitted at a finer packing, when asked for
  double finer_factor = 0;
  std::string dynamic_warning;  // Simulator::dynamic_warning(): empty while the runs are quasi-static
  std::string scaled_sizes;     // scaled_to_base_run's lines: plausible sizes from the base run
};

std::string contrast_markdown(const ContrastReport& r);
std::string contrast_json(const ContrastReport& r);
// One panel per set: measured contrast with its +-2u band, the base model's and the named
// effect's simulated contrasts (gnuplot).
void plot_contrasts(const ContrastReport& r, const std::filesystem::path& image);

}  // namespace shard
