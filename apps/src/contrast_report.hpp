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

#include "measure_plan.hpp"
#include "shard/io/json.hpp"
#include "shard/measure/contrast_diagnosis.hpp"
#include "shard/measure/effect_library.hpp"

namespace shard {

struct ContrastOptionsCli {
  std::vector<std::filesystem::path> sets;
  std::string reference;
  std::filesystem::path library, out;
  ModelPlan model;
  SimulationOptions sim;
  std::vector<std::string> only;
  std::vector<std::string> assumptions;  // --assumption section.key=value (diagnose-sets)
  measure::ContrastDiagnosisOptions diagnosis;  // base fit, confirmation, pairs, decision rules
};

void add_contrast_options(CLI::App* cmd, ContrastOptionsCli& o);
// The library (--effects, or effects.toml beside the scene) and its --only selection.
std::vector<measure::CandidateEffect> contrast_effects(const ContrastOptionsCli& o);
// What a contrast diagnosis is rendered from: the sets (names, folders) and the result.
struct ContrastReport {
  const measure::ContrastSets& sets;
  const measure::ContrastDiagnosis& result;
};

std::string contrast_markdown(const ContrastReport& r);
io::Json contrast_json(const ContrastReport& r);
// One panel per set: measured contrast with its +-2u band, the base model's and the named
// effect's simulated contrasts (gnuplot).
void plot_contrasts(const ContrastReport& r, const std::filesystem::path& image);

}  // namespace shard
