// `shard diagnose SET_A SET_B ... [--reference SET]` (routed to diagnose-sets): binds the options,
// runs the contrast diagnosis (shard/measure/contrast_diagnosis.hpp) on the DEM ensemble and
// renders its result as diagnose.md, diagnose.json and contrasts.png.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "contrast_report.hpp"
#include "shard/driver/output_folder.hpp"
#include "measure_commands.hpp"
#include "shard/app/commands.hpp"
#include "shard/measure/report.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

}  // namespace

void add_diagnose_sets_command(CLI::App& app, CommandContext& ctx) {
  auto o = std::make_shared<ContrastOptionsCli>();
  auto* cmd = app.add_subcommand("diagnose-sets", "which library effect makes each measurement set differ from the "
                                                  "reference (also: shard diagnose SET_A SET_B ...)");
  add_contrast_options(cmd, *o);
  cmd->add_option("--finer", o->diagnosis.finer,
                  "also fit the base at generator diameters this factor smaller (e.g. 0.8) and report whether the "
                  "form error shrinks with resolution")
      ->check(CLI::Range(0.2, 1.0));
  cmd->add_option("--confirm", o->diagnosis.confirm, "best effects per set confirmed by simulated runs at their fitted size");
  cmd->add_option("--pairs", o->diagnosis.pairs,
                  "pairs of effects simulated per set when the closest single effect leaves a remainder beyond "
                  "noise (two effects at once; 0: single effects only)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--pair-iterations", o->diagnosis.pair_iterations,
                  "runs per pair: the first at the linear sizes, later ones a Gauss-Newton step each")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--assumption", o->assumptions,
                  "a condition the base model assumes, moved to this value (section.key=value, repeatable): the base "
                  "and each set's shown model are run again there, and the report says how much each verdict leans "
                  "on it");
  cmd->add_option("--out", o->out, "folder for diagnose.md, diagnose.json and contrasts.png")->default_val("diagnose");
  cmd->callback([o, &ctx] {
    o->diagnosis.assumptions = parse_overrides(o->assumptions);
    const ContrastSets sets = read_contrast_sets(o->sets, o->reference);
    const auto library = contrast_effects(*o);
    prepare_output_folder(o->out, "--out");  // after the cheap reads, before the simulations
    EnsembleSimulator simulator(o->sim, ctx.plugin_dirs);
    const ContrastDiagnosis result = diagnose_contrasts(sets, simulator, o->model, library, o->diagnosis, std::cerr);
    const ContrastReport report{sets, result};
    const std::string md = contrast_markdown(report);
    std::ofstream(o->out / "diagnose.md") << md;
    io::write_json(o->out / "diagnose.json", contrast_json(report));
    try {
      plot_contrasts(report, o->out / "contrasts.png");
    } catch (const std::exception& e) {
      fmt::print(stderr, "warning: no plot: {}\n", e.what());
    }
    fmt::print("{}", md);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
