// `shard compare`, `shard synth` and `shard diagnose`: the measurement workflow of issue 7.
// Simulations go through run_scene; identical runs (same scene text, overrides and seed) are
// read back from a cache folder instead of being repeated.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/os.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>

#include "shard/app/commands.hpp"
#include "shard/app/run_command.hpp"
#include "shard/measure/comparison.hpp"
#include "shard/measure/diagnosis.hpp"
#include "shard/measure/measurements.hpp"
#include "shard/measure/report.hpp"
#include "shard/measure/synthetic.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

// A scene with its overrides, run once per packing seed.
struct SimulationPlan {
  fs::path scene;
  std::vector<std::string> overrides;
  int seeds = 3;
  long first_seed = 1;
  fs::path work_dir = "shard_work";
  double machine_compliance = 0;  // m/N, applied to the simulated curve (a series spring)
};

std::string file_text(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", p.string()));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// FNV-1a: a stable key for the run cache (std::hash may differ between builds).
std::string cache_key(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : text) h = (h ^ ch) * 1099511628211ull;
  return fmt::format("{:016x}", h);
}

Curve run_or_cached(const SimulationPlan& plan, long seed, const std::vector<fs::path>& plugin_dirs) {
  std::string key_text = file_text(plan.scene);
  std::vector<std::string> overrides = plan.overrides;
  overrides.push_back(fmt::format("simulation.seed={}", seed));
  for (const auto& o : overrides) key_text += "\n--set " + o;
  const std::string key = cache_key(key_text);
  const fs::path cached = plan.work_dir / "cache" / (key + ".csv");
  Curve c;
  if (fs::exists(cached)) {
    Metadata unit;
    unit.load_cell_uncertainty = 1;  // placeholder: simulated curves carry no sensor noise
    c = read_curve(cached, unit);
  } else {
    RunOptions run;
    run.scene = plan.scene;
    run.overrides = overrides;
    run.out_dir = plan.work_dir / "runs" / key;
    run.plugin_dirs = plugin_dirs;
    run.quiet = true;
    std::ostringstream log;
    const RunSummary s = run_scene(run, log);
    c.time = s.time_series;
    c.displacement = s.displacement;
    c.force = s.load;
    fs::create_directories(cached.parent_path());
    auto out = fmt::output_file(cached.string());
    out.print("# {} seed {}\ntime,displacement,force\n", plan.scene.string(), seed);
    for (std::size_t k = 0; k < c.size(); ++k) out.print("{:.12g},{:.12g},{:.12g}\n", c.time[k], c.displacement[k], c.force[k]);
  }
  c.u_force.assign(c.size(), 0.0);
  c.u_displacement.assign(c.size(), 0.0);
  return plan.machine_compliance > 0 ? with_machine_compliance(c, plan.machine_compliance) : c;
}

std::vector<Specimen> simulate(const SimulationPlan& plan, const std::vector<fs::path>& plugin_dirs) {
  std::vector<Specimen> out;
  for (int k = 0; k < plan.seeds; ++k) {
    Specimen s;
    s.id = fmt::format("sim_seed{}", plan.first_seed + k);
    s.curve = run_or_cached(plan, plan.first_seed + k, plugin_dirs);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<Specimen> at_rate(const MeasurementSet& set, double rate) {
  std::vector<Specimen> out;
  const auto rates = set.loading_rates();
  if (rate <= 0 && rates.size() > 1)
    throw std::runtime_error(fmt::format("the measurements have {} loading rates; choose one with --rate", rates.size()));
  for (const auto& s : set.specimens)
    if (rate <= 0 || std::abs(s.loading_rate - rate) <= 1e-9 * rate) out.push_back(s);
  if (out.empty()) throw std::runtime_error(fmt::format("no specimen at loading rate {} m/s", rate));
  return out;
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

void add_plan_options(CLI::App* cmd, SimulationPlan& plan) {
  cmd->add_option("--scene", plan.scene, "model scene (.toml)");
  cmd->add_option("--set", plan.overrides, "override a scene key, e.g. --set bond.youngs_modulus=13e6");
  cmd->add_option("--seeds", plan.seeds, "packing-seed replicates")->check(CLI::PositiveNumber);
  cmd->add_option("--first-seed", plan.first_seed, "first packing seed");
  cmd->add_option("--work", plan.work_dir, "folder for runs and the run cache");
  cmd->add_option("--machine-compliance", plan.machine_compliance,
                  "load-frame compliance C in m/N added to the simulated displacement (w + C F)");
}

void add_compare(CLI::App& app, CommandContext& ctx) {
  struct Options {
    fs::path measurements, out = "compare";
    std::vector<fs::path> simulated;
    double rate = 0;
    SimulationPlan plan;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("compare", "compare measured curves with simulated ones: features, regimes, verdict, plot");
  cmd->add_option("measurements", o->measurements, "measurement folder (docs/measurements.md)")->required();
  cmd->add_option("--sim", o->simulated, "simulated curve CSV(s) (time,displacement,force), e.g. from shard run");
  cmd->add_option("--rate", o->rate, "compare the specimens at this loading rate (m/s)");
  cmd->add_option("--out", o->out, "folder for compare.md, compare.json, compare.png");
  add_plan_options(cmd, o->plan);
  cmd->callback([o, &ctx] {
    const MeasurementSet set = read_measurements(o->measurements);
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
    if (!o->plan.scene.empty())
      for (auto& s : simulate(o->plan, ctx.plugin_dirs)) sims.push_back(std::move(s));
    if (sims.empty()) throw std::runtime_error("compare: give simulated curves with --sim or a model with --scene");
    const Comparison c = compare(at_rate(set, o->rate), set.metadata, sims);
    fs::create_directories(o->out);
    write_text(o->out / "compare.md", comparison_markdown(c));
    write_text(o->out / "compare.json", comparison_json(c));
    plot_comparison(c, o->out / "compare.png", fmt::format("{} vs model", set.metadata.name));
    fmt::print("{}\nwritten: {}/compare.md, compare.json, compare.png\n", comparison_markdown(c), o->out.string());
    ctx.exit_code = 0;
  });
}

void add_synth(CLI::App& app, CommandContext& ctx) {
  struct Options {
    SimulationPlan plan;
    SensorModel sensor;
    fs::path out = "synthetic";
    std::string name = "synthetic";
    double length = 0.18, width = 0.03, height = 0.035, span = 0.17, pin_distance = 0.08, rate = 0.01;
    std::uint64_t noise_seed = 1;
  };
  auto o = std::make_shared<Options>();
  o->plan.first_seed = 1001;  // other packings than the model's default seeds 1, 2, 3
  auto* cmd = app.add_subcommand("synth", "synthetic measurements from a truth scene plus a testing-machine model");
  add_plan_options(cmd, o->plan);
  cmd->get_option("--scene")->required();
  cmd->add_option("--out", o->out, "measurement folder to write");
  cmd->add_option("--name", o->name, "name in metadata.toml");
  cmd->add_option("--scatter", o->sensor.specimen_scatter, "specimen-to-specimen force scale sd (1)");
  cmd->add_option("--force-noise", o->sensor.force_noise, "load-cell noise sd per reading (N)");
  cmd->add_option("--force-offset", o->sensor.force_offset, "load-cell tare sd per specimen (N)");
  cmd->add_option("--displacement-step", o->sensor.displacement_step, "displacement resolution (m)");
  cmd->add_option("--noise-seed", o->noise_seed, "seed of the sensor noise");
  cmd->add_option("--length", o->length, "specimen length in specimens.csv (m)");
  cmd->add_option("--width", o->width, "specimen width (m)");
  cmd->add_option("--height", o->height, "specimen height (m)");
  cmd->add_option("--span", o->span, "support distance (m)");
  cmd->add_option("--pin-distance", o->pin_distance, "loading-pin distance (m)");
  cmd->add_option("--rate", o->rate, "loading rate written to specimens.csv (m/s)");
  cmd->callback([o, &ctx] {
    MeasurementSet set;
    set.metadata.name = o->name;
    set.metadata.load_cell_uncertainty = std::max(std::hypot(o->sensor.force_noise, o->sensor.force_offset), 1e-12);
    set.metadata.displacement_uncertainty = o->sensor.displacement_step / std::sqrt(12.0);
    std::mt19937_64 rng(o->noise_seed);
    SimulationPlan truth = o->plan;
    truth.machine_compliance = 0;  // the sensor model applies it to the true force
    o->sensor.machine_compliance = o->plan.machine_compliance;
    for (auto& sim : simulate(truth, ctx.plugin_dirs)) {
      Specimen s;
      s.id = sim.id;
      s.length = o->length, s.width = o->width, s.height = o->height;
      s.span = o->span, s.pin_distance = o->pin_distance, s.loading_rate = o->rate;
      s.curve = record(sim.curve, o->sensor, rng);
      set.specimens.push_back(std::move(s));
    }
    write_measurements(set, o->out);
    fmt::print("wrote {} specimens to {}\n", set.specimens.size(), o->out.string());
    ctx.exit_code = 0;
  });
}

// An effect for diagnose: "name:section.key=value[;section.key=value]" or
// "name:machine_compliance=C" (the series spring, applied to the simulated curve).
struct EffectSpec {
  std::string name;
  std::vector<std::string> overrides;
  double machine_compliance = 0;
  double trial_size = 1;
};

EffectSpec parse_effect(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos || colon == 0)
    throw std::runtime_error(fmt::format("--effect '{}': write name:section.key=value", text));
  EffectSpec e;
  e.name = text.substr(0, colon);
  std::string rest = text.substr(colon + 1);
  std::size_t start = 0;
  while (start <= rest.size()) {
    const auto semi = rest.find(';', start);
    const std::string item = rest.substr(start, semi == std::string::npos ? std::string::npos : semi - start);
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw std::runtime_error(fmt::format("--effect '{}': '{}' has no '='", text, item));
    const double value = std::stod(item.substr(eq + 1));
    if (item.substr(0, eq) == "machine_compliance") e.machine_compliance = value;
    else e.overrides.push_back(item);
    if (start == 0) e.trial_size = value;  // the first setting is the effect's size
    if (semi == std::string::npos) break;
    start = semi + 1;
  }
  return e;
}

void add_diagnose(CLI::App& app, CommandContext& ctx) {
  struct Options {
    fs::path measurements, out = "diagnose";
    double rate = 0;
    SimulationPlan plan;
    std::vector<std::string> params;   // section.key=relative_step
    std::vector<std::string> effects;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("diagnose", "rank candidate effects by how much of the model's residual each explains");
  cmd->add_option("measurements", o->measurements, "measurement folder")->required();
  add_plan_options(cmd, o->plan);
  cmd->get_option("--scene")->required();
  cmd->add_option("--rate", o->rate, "loading rate to use (m/s)");
  cmd->add_option("--param", o->params,
                  "base parameter and its current value for the Jacobian, e.g. bond.youngs_modulus=12.8e6")
      ->required();
  cmd->add_option("--effect", o->effects, "candidate effect name:section.key=value (its plausible size)")->required();
  cmd->add_option("--out", o->out, "folder for diagnose.md");
  cmd->callback([o, &ctx] {
    const MeasurementSet set = read_measurements(o->measurements);
    const auto measured = at_rate(set, o->rate);
    auto residual_of = [&](const SimulationPlan& plan) {
      return compare(measured, set.metadata, simulate(plan, ctx.plugin_dirs)).residual_vector();
    };
    const ResidualVector base = residual_of(o->plan);
    std::vector<std::vector<double>> jacobian;
    for (const auto& p : o->params) {
      const auto eq = p.find('=');
      if (eq == std::string::npos) throw std::runtime_error(fmt::format("--param '{}': write section.key=value", p));
      const double value = std::stod(p.substr(eq + 1));
      SimulationPlan stepped = o->plan;
      stepped.overrides.push_back(fmt::format("{}={:.9g}", p.substr(0, eq), 1.05 * value));  // +5 %
      const ResidualVector r = residual_of(stepped);
      if (r.names != base.names) throw std::runtime_error("diagnose: a parameter step changed the residual components");
      std::vector<double> column;
      for (std::size_t i = 0; i < r.values.size(); ++i) column.push_back((r.values[i] - base.values[i]) / 0.05);
      jacobian.push_back(column);
    }
    std::vector<EffectSignature> signatures;
    for (const auto& text : o->effects) {
      const EffectSpec e = parse_effect(text);
      SimulationPlan on = o->plan;
      on.overrides.insert(on.overrides.end(), e.overrides.begin(), e.overrides.end());
      on.machine_compliance = e.machine_compliance;
      const ResidualVector r = residual_of(on);
      if (r.names != base.names) throw std::runtime_error(fmt::format("diagnose: effect '{}' changed the residual components", e.name));
      EffectSignature s{e.name, e.trial_size, {}};
      for (std::size_t i = 0; i < r.values.size(); ++i) s.signature.push_back(r.values[i] - base.values[i]);
      signatures.push_back(s);
    }
    const Diagnosis d = diagnose(base.names, base.values, jacobian, signatures);
    std::string md = fmt::format("**Diagnosis: {}** (residual chi^2 {:.1f}, after the base parameters {:.1f}, p = {:.3g})\n\n",
                                 d.verdict, d.chi_square, d.chi_square_unabsorbed, d.p_value);
    md += "| effect | score | p-value | explained | estimated size | dAIC | dBIC | explains |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& s : d.ranking) {
      std::string explains;
      for (const auto& x : s.explains) explains += (explains.empty() ? "" : ", ") + x;
      md += fmt::format("| {} | {:.2f} | {:.3g} | {:.0f} % | {:+.4g} | {:+.1f} | {:+.1f} | {} |\n", s.name, s.score,
                        s.p_value, 100 * s.explained, s.size, s.delta_aic, s.delta_bic, explains);
    }
    for (const auto& [a, b] : d.indistinguishable)
      md += fmt::format("\n{} and {} have nearly parallel signatures: these data cannot tell them apart "
                        "(a second loading rate, an unloading cycle or fragment sizes may).\n",
                        a, b);
    fs::create_directories(o->out);
    write_text(o->out / "diagnose.md", md);
    fmt::print("{}", md);
    ctx.exit_code = 0;
  });
}

}  // namespace

void add_measure_command(CLI::App& app, CommandContext& ctx) {
  add_compare(app, ctx);
  add_synth(app, ctx);
  add_diagnose(app, ctx);
}

}  // namespace shard
