// `shard compare` and `shard synth`, and the registration of the whole measurement workflow
// (diagnose: measure_diagnose.cpp, calibrate-effect: measure_calibrate.cpp, history:
// measure_history.cpp). Simulations go through the RunPool (measure_runner.hpp): cached by their
// resolved scene text, run in parallel child processes.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "measure_commands.hpp"
#include "measure_plan.hpp"
#include "model_history.hpp"
#include "shard/driver/output_folder.hpp"
#include "shard/io/json.hpp"
#include "shard/app/commands.hpp"
#include "shard/measure/comparison.hpp"
#include "shard/measure/measurements.hpp"
#include "shard/measure/report.hpp"
#include "shard/measure/synthetic.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

// compare.md: one rate as before; several rates, the joint NRMSE and chi-square, then each rate.
std::string rate_comparison_markdown(const RateComparison& rc, const std::string& warning) {
  std::string md = warning.empty() ? "" : fmt::format("**Warning.** {}.\n\n", warning);
  if (rc.at.size() == 1) return md + comparison_markdown(rc.at.front());
  md += fmt::format("{} loading rates compared at once: joint NRMSE = {:.2f} % (RMS of the rates'), chi-square = "
                    "{:.1f}.\n",
                    rc.at.size(), 100 * rc.nrmse(), rc.chi_square());
  for (std::size_t k = 0; k < rc.at.size(); ++k)
    md += fmt::format("\n## At {:g} m/s\n\n{}", rc.rates[k], comparison_markdown(rc.at[k]));
  return md;
}

// compare.json's format: raise it when a key changes meaning or disappears.
constexpr int kCompareFormatVersion = 1;

// compare.json: one rate, the comparison's keys; several, {rates, nrmse, chi_square, at: [...]}.
// Either carries "dynamic_warning" when the model is dynamic at the data's rate.
io::Json rate_comparison_json(const RateComparison& rc, const std::string& warning) {
  io::Json j = io::json_document(kCompareFormatVersion);
  if (rc.at.size() == 1) {
    j.update(comparison_json(rc.at.front()));
  } else {
    j["rates"] = rc.rates;
    j["nrmse"] = rc.nrmse();
    j["chi_square"] = rc.chi_square();
    j["at"] = io::Json::array();
    for (const auto& c : rc.at) j["at"].push_back(comparison_json(c));
  }
  if (!warning.empty()) j["dynamic_warning"] = warning;
  return j;
}

void add_compare(CLI::App& app, CommandContext& ctx) {
  struct Options {
    fs::path measurements, out = "compare";
    std::vector<fs::path> simulated;
    double rate = 0;
    std::string label = "base model";
    ModelPlan model;
    SimulationOptions sim;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("compare", "compare measured curves with simulated ones: features, regimes, verdict, plot");
  cmd->add_option("measurements", o->measurements, "measurement folder (docs/how-to/bring-lab-data.md)")->required();
  cmd->add_option("--sim", o->simulated, "simulated curve CSV(s) (time,displacement,force), e.g. from shard run");
  cmd->add_option("--rate", o->rate, "compare the specimens at this loading rate (m/s)");
  cmd->add_option("--out", o->out, "folder for compare.md, compare.json, compare.png");
  cmd->add_option("--label", o->label, "name of this model version in the history");
  add_simulation_options(cmd, o->model, o->sim);
  cmd->callback([o, &ctx] {
    const MeasurementSet set = read_measurements(o->measurements);
    prepare_output_folder(o->out, "--out");  // after the cheap reads, before the simulations
    CompareOptions options;
    options.judge_fracture = o->sim.judge_fracture;
    options.score_reference = o->sim.score_reference;
    RateComparison rc;
    std::string warning;
    double ke = 0;
    if (!o->model.scene.empty()) {
      if (!o->simulated.empty())
        throw std::runtime_error("compare: give a model with --scene or simulated curves with --sim, not both");
      // Every rate of the set (or --rate's), the model run at each: one comparison per rate and
      // one joint residual, in one history entry.
      EnsembleSimulator simulator(o->sim, ctx.plugin_dirs);
      rc = simulate_and_compare(simulator, rate_groups(set, o->rate), set.metadata, {o->model}, std::cerr).front();
      ke = simulator.max_kinetic_to_elastic();
      warning = simulator.dynamic_warning();
    } else {
      if (o->simulated.empty()) throw std::runtime_error("compare: give simulated curves with --sim or a model with --scene");
      std::vector<Specimen> sims;
      Metadata unit;
      unit.load_cell_uncertainty = 1;
      for (const auto& f : o->simulated) {
        Specimen s;
        s.id = f.stem().string();
        s.curve = read_curve(f, unit);
        s.curve.u_force.assign(s.curve.size(), 0.0);
        sims.push_back(std::move(s));
      }
      const std::vector<Specimen> measured = specimens_at_rate(set, o->rate);
      rc.rates = {measured.front().loading_rate};
      rc.at = {compare(measured, set.metadata, sims, options)};
    }
    const std::string md = rate_comparison_markdown(rc, warning);
    std::ofstream(o->out / "compare.md") << md;
    io::write_json(o->out / "compare.json", rate_comparison_json(rc, warning));
    for (std::size_t k = 0; k < rc.at.size(); ++k)
      plot_comparison(rc.at[k],
                      o->out / (rc.at.size() > 1 ? fmt::format("compare_rate{:g}.png", rc.rates[k]) : "compare.png"),
                      fmt::format("{} vs {}{}", set.metadata.name, o->label,
                                  rc.at.size() > 1 ? fmt::format(" at {:g} m/s", rc.rates[k]) : ""));
    fmt::print("{}\n", md);
    if (!warning.empty()) fmt::print(stderr, "warning: {}\n", warning);
    if (!o->model.scene.empty()) {
      fmt::print("largest kinetic/elastic energy ratio before breakage: {:.2g} (quasi-static at or below {:g})\n", ke,
                 kDynamicKineticToElastic);
      HistoryEntry h = history_entry("compare", o->label, rc);
      for (const auto& s : o->model.overrides) {
        if (const auto* d = std::get_if<double>(&s.value)) h.parameters[s.key] = *d;
        if (const auto* i = std::get_if<std::int64_t>(&s.value)) h.parameters[s.key] = static_cast<double>(*i);
      }
      if (o->model.machine_compliance > 0) h.parameters["machine_compliance"] = o->model.machine_compliance;
      append_history(o->sim.work_dir, h);
    }
    fmt::print("written: {}/compare.md, compare.json, {}\n", o->out.string(),
               rc.at.size() > 1 ? "compare_rate<rate>.png" : "compare.png");
    ctx.exit_code = 0;
  });
}

struct SynthOptions {
  ModelPlan model;
  SimulationOptions sim;
  SensorModel sensor;
  fs::path out = "synthetic";
  std::string name = "synthetic";
  // Unset: read from the scene (its walls and generated packing; its pin speed).
  std::optional<double> length, width, height, span, pin_distance;
  std::vector<double> rates;
  std::uint64_t noise_seed = 1;
  TestConditions test;  // how the simulated lab runs and records its tests
};

void add_synth_options(CLI::App* cmd, SynthOptions& o) {
  add_simulation_options(cmd, o.model, o.sim);
  cmd->get_option("--scene")->required();
  cmd->add_option("--out", o.out, "measurement folder to write");
  cmd->add_option("--name", o.name, "name in metadata.toml");
  cmd->add_option("--scatter", o.sensor.specimen_scatter, "specimen-to-specimen force scale sd (1)");
  cmd->add_option("--force-noise", o.sensor.force_noise, "load-cell noise sd per reading (N)");
  cmd->add_option("--force-offset", o.sensor.force_offset, "load-cell tare sd per specimen (N)");
  cmd->add_option("--displacement-step", o.sensor.displacement_step, "displacement resolution (m)");
  cmd->add_option("--seating-gap", o.sensor.seating_gap,
                  "closure gap of rough specimen faces (m): a toe w + g F / (F + F_h), outside the effect library");
  cmd->add_option("--seating-half-force", o.sensor.seating_half_force, "force at half closure F_h (N)");
  cmd->add_option("--noise-seed", o.noise_seed, "seed of the sensor noise");
  cmd->add_option("--length", o.length, "specimen length in specimens.csv (m; default: the scene's packing)");
  cmd->add_option("--width", o.width, "specimen width (m; default: the scene's packing)");
  cmd->add_option("--height", o.height, "specimen height (m; default: the scene's packing)");
  cmd->add_option("--span", o.span, "support distance (m; default: the scene's supports)");
  cmd->add_option("--pin-distance", o.pin_distance, "loading-pin distance (m; default: the scene's pins)");
  cmd->add_option("--rate,--rates", o.rates,
                  "loading rate(s) of the pins (m/s), comma-separated: the truth is run at each, its specimens are "
                  "replicates at that rate (default: the scene's pin speed)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seating-preload", o.test.seating_preload,
                  "record each curve from where the force first reaches this preload (N), with t = 0 and d = 0 there; "
                  "written to metadata.toml [test]")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--zero-offset", o.test.zero_offset,
                  "a known load-cell zero offset (N) added to every recorded force and written to metadata.toml, "
                  "where the reader subtracts it");
  cmd->add_option("--ramp", o.test.ramp, "the pins' acceleration to the loading rate: 1-cos, linear or none")
      ->check(CLI::IsMember({"1-cos", "linear", "none"}));
  cmd->add_option("--ramp-time", o.test.ramp_time, "time of the --ramp in s (lab time)")->check(CLI::PositiveNumber);
  cmd->add_option("--grain-size", o.test.grain_size, "grain size written to metadata.toml (m)")->check(CLI::PositiveNumber);
  cmd->add_option("--fragment-size-threshold", o.test.fragment_size_threshold,
                  "fragments smaller than this (m) are not recorded; written to metadata.toml")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--notes", o.test.notes, "free text for metadata.toml [test] notes");
}

// The truth run at each rate and recorded as the lab of the options would.
void synthesize(SynthOptions& o, const CommandContext& ctx) {
  prepare_output_folder(o.out, "--out");
  if (o.test.has_ramp() != (o.test.ramp_time > 0))
    throw std::runtime_error(o.test.has_ramp() ? fmt::format("--ramp {} needs --ramp-time (s)", o.test.ramp)
                                                : "--ramp-time needs --ramp 1-cos or --ramp linear");
  SyntheticLab lab{o.name, o.sensor, o.test, o.noise_seed};
  lab.sensor.machine_compliance = o.model.machine_compliance;
  ModelPlan truth = o.model;
  truth.machine_compliance = 0;  // the sensor model applies it to the true force
  EnsembleSimulator simulator(o.sim, ctx.plugin_dirs);
  // The truth runs with the lab's ramp and fragment threshold; the preload zeroes the recorded
  // (noisy, compliant) signal, as the machine does.
  TestConditions runs = o.test;
  runs.seating_preload = 0;
  simulator.use_test_conditions(runs);
  if (o.rates.empty()) o.rates.push_back(simulator.pool().fixture().scene_rate(truth.scene, truth.overrides));
  SpecimenSetup setup;
  if (!o.length || !o.width || !o.height || !o.span || !o.pin_distance)
    setup = simulator.pool().fixture().specimen_setup(truth.scene, truth.overrides, o.sim.first_seed);
  Specimen geometry;
  geometry.length = o.length.value_or(setup.length), geometry.width = o.width.value_or(setup.width);
  geometry.height = o.height.value_or(setup.height), geometry.span = o.span.value_or(setup.span);
  geometry.pin_distance = o.pin_distance.value_or(setup.pin_distance);
  std::vector<ModelPlan> at_rates;
  for (double r : o.rates) {
    at_rates.push_back(truth);
    at_rates.back().loading_rate = r;
  }
  const MeasurementSet set = synthetic_set(simulator.simulate(at_rates, std::cerr), o.rates, geometry, lab);
  write_measurements(set, o.out);
  fmt::print("wrote {} specimens to {} (largest kinetic/elastic ratio {:.2g})\n", set.specimens.size(),
             o.out.string(), simulator.max_kinetic_to_elastic());
  if (const std::string w = simulator.dynamic_warning(); !w.empty()) fmt::print(stderr, "warning: {}\n", w);
}

void add_synth(CLI::App& app, CommandContext& ctx) {
  auto o = std::make_shared<SynthOptions>();
  o->sim.first_seed = 1001;  // other packings than the model's default seeds 1, 2, 3
  auto* cmd = app.add_subcommand("synth", "synthetic measurements from a truth scene plus a testing-machine model");
  add_synth_options(cmd, *o);
  cmd->callback([o, &ctx] {
    synthesize(*o, ctx);
    ctx.exit_code = 0;
  });
}

}  // namespace

void add_measure_command(CLI::App& app, CommandContext& ctx) {
  add_compare(app, ctx);
  add_synth(app, ctx);
  add_diagnose_command(app, ctx);
  add_calibrate_effect_command(app, ctx);
  add_diagnose_sets_command(app, ctx);
  add_calibrate_contrast_command(app, ctx);
  add_history_command(app, ctx);
}

}  // namespace shard
