// `shard compare` and `shard synth`, and the registration of the whole measurement workflow
// (diagnose: measure_diagnose.cpp, calibrate-effect: measure_calibrate.cpp, history:
// measure_history.cpp). Simulations go through the RunPool (measure_runner.hpp): cached by their
// resolved scene text, run in parallel child processes.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <random>

#include "measure_commands.hpp"
#include "measure_plan.hpp"
#include "output_folder.hpp"
#include "shard/app/commands.hpp"
#include "shard/measure/comparison.hpp"
#include "shard/measure/measurements.hpp"
#include "shard/measure/report.hpp"
#include "shard/measure/synthetic.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

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
  cmd->add_option("measurements", o->measurements, "measurement folder (docs/measurements.md)")->required();
  cmd->add_option("--sim", o->simulated, "simulated curve CSV(s) (time,displacement,force), e.g. from shard run");
  cmd->add_option("--rate", o->rate, "compare the specimens at this loading rate (m/s)");
  cmd->add_option("--out", o->out, "folder for compare.md, compare.json, compare.png");
  cmd->add_option("--label", o->label, "name of this model version in the history");
  add_simulation_options(cmd, o->model, o->sim);
  cmd->callback([o, &ctx] {
    const MeasurementSet set = read_measurements(o->measurements);
    prepare_output_folder(o->out, "--out");  // after the cheap reads, before the simulations
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
    double ke = 0;
    const std::vector<Specimen> measured = specimens_at_rate(set, o->rate);
    if (!o->model.scene.empty()) {
      Simulator simulator(o->sim, ctx.plugin_dirs);
      simulator.check_inputs(o->model, measured);
      // The model runs at the compared specimens' rate: --rate, or the data's only rate.
      const std::vector<double> rates = set.loading_rates();
      o->model.loading_rate = o->rate > 0 ? o->rate : rates.size() == 1 ? rates.front() : 0.0;
      for (auto& s : simulator.simulate(o->model, std::cerr)) sims.push_back(std::move(s));
      ke = simulator.max_kinetic_to_elastic();
    }
    if (sims.empty()) throw std::runtime_error("compare: give simulated curves with --sim or a model with --scene");
    CompareOptions options;
    options.judge_fracture = o->sim.judge_fracture;
    const Comparison c = compare(measured, set.metadata, sims, options);
    std::ofstream(o->out / "compare.md") << comparison_markdown(c);
    std::ofstream(o->out / "compare.json") << comparison_json(c);
    plot_comparison(c, o->out / "compare.png", fmt::format("{} vs {}", set.metadata.name, o->label));
    fmt::print("{}\n", comparison_markdown(c));
    if (!o->model.scene.empty()) {
      fmt::print("largest kinetic/elastic energy ratio before breakage: {:.2g} (quasi-static below ~1e-2)\n", ke);
      HistoryEntry h = history_entry("compare", o->label, c);
      for (const auto& s : o->model.overrides)
        if (const auto eq = s.find('='); eq != std::string::npos) try {
            h.parameters[s.substr(0, eq)] = std::stod(s.substr(eq + 1));
          } catch (const std::exception&) {
          }
      if (o->model.machine_compliance > 0) h.parameters["machine_compliance"] = o->model.machine_compliance;
      append_history(o->sim.work_dir, h);
    }
    fmt::print("written: {}/compare.md, compare.json, compare.png\n", o->out.string());
    ctx.exit_code = 0;
  });
}

void add_synth(CLI::App& app, CommandContext& ctx) {
  struct Options {
    ModelPlan model;
    SimulationOptions sim;
    SensorModel sensor;
    fs::path out = "synthetic";
    std::string name = "synthetic";
    // Unset: read from the scene (its walls and generated packing; its pin speed).
    std::optional<double> length, width, height, span, pin_distance;
    std::vector<double> rates;
    std::uint64_t noise_seed = 1;
  };
  auto o = std::make_shared<Options>();
  o->sim.first_seed = 1001;  // other packings than the model's default seeds 1, 2, 3
  auto* cmd = app.add_subcommand("synth", "synthetic measurements from a truth scene plus a testing-machine model");
  add_simulation_options(cmd, o->model, o->sim);
  cmd->get_option("--scene")->required();
  cmd->add_option("--out", o->out, "measurement folder to write");
  cmd->add_option("--name", o->name, "name in metadata.toml");
  cmd->add_option("--scatter", o->sensor.specimen_scatter, "specimen-to-specimen force scale sd (1)");
  cmd->add_option("--force-noise", o->sensor.force_noise, "load-cell noise sd per reading (N)");
  cmd->add_option("--force-offset", o->sensor.force_offset, "load-cell tare sd per specimen (N)");
  cmd->add_option("--displacement-step", o->sensor.displacement_step, "displacement resolution (m)");
  cmd->add_option("--seating-gap", o->sensor.seating_gap,
                  "closure gap of rough specimen faces (m): a toe w + g F / (F + F_h), outside the effect library");
  cmd->add_option("--seating-half-force", o->sensor.seating_half_force, "force at half closure F_h (N)");
  cmd->add_option("--noise-seed", o->noise_seed, "seed of the sensor noise");
  cmd->add_option("--length", o->length, "specimen length in specimens.csv (m; default: the scene's packing)");
  cmd->add_option("--width", o->width, "specimen width (m; default: the scene's packing)");
  cmd->add_option("--height", o->height, "specimen height (m; default: the scene's packing)");
  cmd->add_option("--span", o->span, "support distance (m; default: the scene's supports)");
  cmd->add_option("--pin-distance", o->pin_distance, "loading-pin distance (m; default: the scene's pins)");
  cmd->add_option("--rate,--rates", o->rates,
                  "loading rate(s) of the pins (m/s), comma-separated: the truth is run at each, its specimens are "
                  "replicates at that rate (default: the scene's pin speed)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  cmd->callback([o, &ctx] {
    prepare_output_folder(o->out, "--out");
    MeasurementSet set;
    set.metadata.name = o->name;
    set.metadata.load_cell_uncertainty = std::max(std::hypot(o->sensor.force_noise, o->sensor.force_offset), 1e-12);
    set.metadata.displacement_uncertainty = o->sensor.displacement_step / std::sqrt(12.0);
    std::mt19937_64 rng(o->noise_seed);
    ModelPlan truth = o->model;
    truth.machine_compliance = 0;  // the sensor model applies it to the true force
    o->sensor.machine_compliance = o->model.machine_compliance;
    Simulator simulator(o->sim, ctx.plugin_dirs);
    if (o->rates.empty()) o->rates.push_back(simulator.pool().scene_rate(truth.scene, truth.overrides));
    SpecimenSetup setup;
    if (!o->length || !o->width || !o->height || !o->span || !o->pin_distance)
      setup = simulator.pool().specimen_setup(truth.scene, truth.overrides, o->sim.first_seed);
    setup.length = o->length.value_or(setup.length), setup.width = o->width.value_or(setup.width);
    setup.height = o->height.value_or(setup.height), setup.span = o->span.value_or(setup.span);
    setup.pin_distance = o->pin_distance.value_or(setup.pin_distance);
    std::vector<ModelPlan> at_rates;
    for (double r : o->rates) {
      at_rates.push_back(truth);
      at_rates.back().loading_rate = r;
    }
    const auto sims = simulator.simulate(at_rates, std::cerr);
    for (std::size_t k = 0; k < sims.size(); ++k)
      for (const auto& sim : sims[k]) {
        Specimen s;
        s.id = o->rates.size() > 1 ? fmt::format("{}_rate{:g}", sim.id, o->rates[k]) : sim.id;
        s.length = setup.length, s.width = setup.width, s.height = setup.height;
        s.span = setup.span, s.pin_distance = setup.pin_distance, s.loading_rate = o->rates[k];
        s.curve = record(sim.curve, o->sensor, rng);
        // What a lab notes after the test: where the crack is and the pieces (sieved sizes).
        s.crack_position = sim.crack_position;
        s.fragment_sizes = sim.fragment_sizes;
        s.fragment_count = sim.fragment_count;
        set.specimens.push_back(std::move(s));
      }
    write_measurements(set, o->out);
    fmt::print("wrote {} specimens to {} (largest kinetic/elastic ratio {:.2g})\n", set.specimens.size(),
               o->out.string(), simulator.max_kinetic_to_elastic());
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
