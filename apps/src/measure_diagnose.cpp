// `shard diagnose MEASUREMENTS` (one set, no --reference): binds the options, runs the stepwise
// single-set diagnosis (shard/measure/set_diagnosis.hpp) on the DEM ensemble and renders its result
// as diagnose.md and diagnose.json (set_diagnosis_report.hpp).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <memory>

#include "measure_commands.hpp"
#include "measure_plan.hpp"
#include "option_checks.hpp"
#include "set_diagnosis_report.hpp"
#include "shard/app/commands.hpp"
#include "shard/driver/output_folder.hpp"

namespace shard {

namespace fs = std::filesystem;
using namespace measure;

void add_diagnose_command(CLI::App& app, CommandContext& ctx) {
  struct Options {
    fs::path measurements, out = "diagnose", library;
    double rate = 0;
    ModelPlan model;
    SimulationOptions sim;
    std::vector<std::string> params;
    std::vector<std::string> only;
    int refit = SetDiagnosisOptions{}.refit;
    int max_effects = SetDiagnosisOptions{}.max_effects;
    int refit_iterations = SetDiagnosisOptions{}.refit_iterations;
    std::string scoring = "own";
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("diagnose", "rank candidate effects by how much of the model's residual each explains");
  cmd->add_option("measurements", o->measurements, "measurement folder")->required();
  add_simulation_options(cmd, o->model, o->sim);
  cmd->get_option("--scene")->required();
  cmd->add_option("--rate", o->rate, "loading rate to use (m/s)");
  cmd->add_option("--param", o->params, "calibrated base parameter section.key (its value is read from the scene)")
      ->required();
  cmd->add_option("--effects", o->library, "candidate-effect library (default: effects.toml next to the scene)");
  cmd->add_option("--only", o->only, "try only these effects of the library (comma-separated)")->delimiter(',');
  cmd->add_option("--refit", o->refit, "effects confirmed by a refit run per step (0: none, the score test decides)")
      ->check(number_from(0, false, "0 (no confirmation runs) or a number of effects"));
  cmd->add_option("--max-effects", o->max_effects,
                  "effects a stepwise diagnosis may add one after the other (1: a single effect)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--refit-iterations", o->refit_iterations,
                  "secant iterations (at most) of a kept effect's refit and of every refit of a later stepwise "
                  "step, each on its own simulated run (default 4; 0: linear refits only)")
      ->check(number_from(0, false, "0 (the linear refit only) or a number of iterations"));
  cmd->add_option("--scoring", o->scoring,
                  "how models are scored: own (each model's band; a refit whose NRMSE rises is not named), frozen "
                  "(the base model's band for every run) or likelihood (own band plus the Gaussian log-variance term)");
  cmd->add_option("--out", o->out, "folder for diagnose.md and diagnose.json");
  cmd->callback([o, &ctx] {
    const MeasurementSet set = read_measurements(o->measurements);
    const MeasuredRates data{rate_groups(set, o->rate), set.metadata, compare_options(o->sim)};
    prepare_output_folder(o->out, "--out");  // after the cheap reads, before the simulations
    const fs::path library = o->library.empty() ? o->model.scene.parent_path() / "effects.toml" : o->library;
    const SetDiagnosisOptions options{o->params, o->refit, o->max_effects, o->refit_iterations,
                                      scoring_from_name(o->scoring)};
    EnsembleSimulator simulator(o->sim, ctx.plugin_dirs);
    const SetDiagnosisResult result = diagnose_set(simulator, data, o->model,
                                                   select_effects(read_effect_library(library), o->only), options,
                                                   std::cerr);
    const SetDiagnosisReport report{result,          o->measurements,   o->model.scene,
                                    library,         o->sim.seeds,      data.coverage(),
                                    o->max_effects,  options.scoring,   o->sim.score_reference};
    const std::string md = set_diagnosis_markdown(report);
    std::ofstream(o->out / "diagnose.md") << md;
    io::write_json(o->out / "diagnose.json", set_diagnosis_json(report));
    fmt::print("{}", md);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
