// `shard calibrate SETS... --reference R --with EFFECT [--with EFFECT2] [--target SET]` (routed to
// calibrate-contrast): binds the options, runs the contrast calibration
// (shard/measure/contrast_calibration.hpp) on the DEM ensemble, and writes calibrate.md,
// calibrate.json and both model versions to <work>/history.jsonl.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>

#include "contrast_report.hpp"
#include "shard/driver/output_folder.hpp"
#include "measure_commands.hpp"
#include "model_history.hpp"
#include "shard/io/json.hpp"
#include "shard/measure/contrast_calibration.hpp"
#include "shard/app/commands.hpp"
#include "shard/measure/report.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

std::string calibration_markdown(const ContrastSets& sets, const ContrastCalibration& c) {
  std::string names, sizes;
  for (std::size_t k = 0; k < c.effects.size(); ++k) {
    names += (k ? " + " : "") + c.effects[k].name;
    sizes += fmt::format("{}{} = {}", k ? ", " : "", c.effects[k].parameter, c.effects[k].sized(c.values[k]));
  }
  std::string md = fmt::format("# Calibration of {} on {} against {}\n\n", names, sets.names[c.target],
                               sets.names[*sets.reference]);
  md += fmt::format("{} after {} evaluations{}.\n\n", sizes, c.evaluations,
                    c.at_bound ? " (at the bound of the range searched: the data ask for more)" : "");
  if (!c.scaled_sizes.empty()) md += "Trial size from the fitted base run: " + c.scaled_sizes + "\n";
  if (!c.scan.empty()) {
    md += "Bracketing scan before the local fit (size: contrast chi^2):";
    for (std::size_t k = 0; k < c.scan.size(); ++k)
      md += fmt::format(" {:.4g}: {:.1f}{}", c.scan[k].first, c.scan[k].second, k + 1 < c.scan.size() ? "," : ".\n");
    md += "\n";
  }
  md += "| model | contrast chi^2 | contrast NRMSE |\n|---|---|---|\n";
  md += fmt::format("| base | {:.2f} | {:.2f} % |\n| base + {} | {:.2f} | {:.2f} % |\n", c.chi_square_before,
                    100 * c.before.nrmse, names, c.chi_square_after, 100 * c.after.nrmse);
  md += fmt::format("\nThe contrast NRMSE fell by {:.0f} %.\n", 100 * (1 - c.after.nrmse / c.before.nrmse));
  return md;
}

// calibrate.json's format (contrast form): raise it when a key changes meaning or disappears.
constexpr int kCalibrationFormatVersion = 2;

io::Json calibration_json(const ContrastSets& sets, const ContrastCalibration& c) {
  std::string names;
  for (const auto& e : c.effects) names += (names.empty() ? "" : " + ") + e.name;
  io::Json j = io::json_document(kCalibrationFormatVersion);
  j["set"] = sets.names[c.target];
  j["reference"] = sets.names[*sets.reference];
  j["effect"] = names;
  j["value"] = c.values.front();
  j["values"] = c.values;
  j["at_bound"] = c.at_bound;
  j["evaluations"] = c.evaluations;
  j["chi_square_before"] = c.chi_square_before;
  j["chi_square_after"] = c.chi_square_after;
  j["nrmse_before"] = c.before.nrmse;
  j["nrmse_after"] = c.after.nrmse;
  j["nrmse_floor"] = c.after.floor;
  return j;
}

// Both model versions in <work>/history.jsonl: the fall of the error, per version.
void record_history(const fs::path& work_dir, const std::string& label, const ContrastCalibration& c) {
  HistoryEntry h0, h1;
  h0.command = h1.command = "calibrate-contrast";
  h0.label = label + " base";
  std::string names;
  for (const auto& e : c.effects) names += (names.empty() ? "" : " + ") + e.name;
  h1.label = label + " + " + names;
  for (const auto& e : c.effects) h1.effects.push_back(e.name);
  const BaseCalibration& cal = c.calibration;
  for (std::size_t k = 0; k < cal.keys.size(); ++k) h0.parameters[cal.keys[k]] = h1.parameters[cal.keys[k]] = cal.values[k];
  for (std::size_t k = 0; k < c.effects.size(); ++k) h1.parameters[c.effects[k].parameter] = c.values[k];
  h0.nrmse = c.before.nrmse, h0.chi_square = c.chi_square_before;
  h1.nrmse = c.after.nrmse, h1.chi_square = c.chi_square_after;
  append_history(work_dir, h0);
  append_history(work_dir, h1);
}

}  // namespace

void add_calibrate_contrast_command(CLI::App& app, CommandContext& ctx) {
  struct Options : ContrastOptionsCli {
    std::vector<std::string> with;
    std::string target, label;
    int max_evaluations = 12;
    bool scan = true;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("calibrate-contrast", "fit an effect's size to one set's difference from the reference "
                                                       "(also: shard calibrate SETS --reference R --with EFFECT)");
  add_contrast_options(cmd, *o);
  cmd->get_option("--reference")->required();
  cmd->add_option("--with", o->with,
                  "the library effect to add; twice for two effects at once (diagnose's 'A + B'), sized jointly")
      ->required()
      ->allow_extra_args(false);  // one name per --with: the sets are positional
  cmd->add_option("--target", o->target, "the set whose difference is fitted (default: the first that is not the reference)");
  cmd->add_option("--max-evaluations", o->max_evaluations,
                  "model evaluations of the local fit (after the bracketing scan; doubled for two effects)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--scan,!--no-scan", o->scan,
               "before the local fit, try 0.5, 1, 2, 4 and 8 trial sizes each way from neutral in one batch and start "
               "from the best (default on; one effect only: two start from their joint linear fit)");
  cmd->add_option("--label", o->label, "name of this model version in the history");
  cmd->add_option("--out", o->out, "folder for calibrate.md and calibrate.png")->default_val("calibrate");
  cmd->callback([o, &ctx] {
    if (o->with.size() > 2)
      throw std::runtime_error(fmt::format("--with given {} times: calibrate fits one effect or two at once", o->with.size()));
    if (o->with.size() == 2 && o->with[0] == o->with[1])
      throw std::runtime_error(fmt::format("--with {} given twice: name two different effects", o->with[0]));
    const ContrastSets sets = read_contrast_sets(o->sets, o->reference);
    std::size_t target = sets.sets.size();
    for (std::size_t k = 0; k < sets.sets.size(); ++k)
      if (k != *sets.reference && (o->target.empty() || sets.names[k] == o->target)) {
        target = k;
        break;
      }
    if (target == sets.sets.size())
      throw std::runtime_error(fmt::format("--target {}: not among the sets given, or it is the reference", o->target));
    const auto library = contrast_effects(*o);
    std::vector<CandidateEffect> chosen;
    for (const auto& name : o->with) chosen.push_back(select_effects(library, {name}).front());
    prepare_output_folder(o->out, "--out");  // after the cheap reads, before the simulations
    EnsembleSimulator simulator(o->sim, ctx.plugin_dirs);
    ContrastCalibrationOptions options;
    options.params = o->diagnosis.params;
    options.base_iterations = o->diagnosis.base_iterations;
    options.decide = o->diagnosis.decide;
    options.max_evaluations = o->max_evaluations;
    options.scan = o->scan;
    options.lab_grain_size = o->diagnosis.lab_grain_size;
    const ContrastCalibration c = calibrate_contrast(sets, target, simulator, o->model, chosen, options, std::cerr);
    const std::string md = calibration_markdown(sets, c);
    std::ofstream(o->out / "calibrate.md") << md;
    io::write_json(o->out / "calibrate.json", calibration_json(sets, c));
    fmt::print("{}", md);
    record_history(o->sim.work_dir, o->label.empty() ? sets.names[target] : o->label, c);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
