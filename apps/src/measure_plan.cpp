#include "measure_plan.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "shard/measure/synthetic.hpp"
#include "run_job.hpp"
#include "shard/measure/significant_digits.hpp"

namespace shard {

namespace fs = std::filesystem;
using namespace measure;

void add_simulation_options(CLI::App* cmd, ModelPlan& model, SimulationOptions& options) {
  cmd->add_option("--scene", model.scene, "model scene (.toml)");
  cmd->add_option_function<std::vector<std::string>>(
      "--set",
      [&model](const std::vector<std::string>& assignments) {
        for (const auto& a : assignments) model.overrides.push_back(SceneOverride::parse(a));
      },
      "override a scene key, e.g. --set bond.youngs_modulus=13e6");
  cmd->add_option("--seeds", options.seeds, "packing-seed replicates")->check(CLI::PositiveNumber);
  cmd->add_option("--first-seed", options.first_seed, "first packing seed");
  cmd->add_option("--work", options.work_dir, "folder for the run cache and history.jsonl");
  cmd->add_option("--workers", options.workers, "simulations run at once (one run each)")->check(CLI::PositiveNumber);
  cmd->add_flag("--isolate", options.isolate,
                "run each simulation in a worker process of its own: a crash in a plugin (a segmentation fault) "
                "fails that run, not the command (costs ~0.3 s of CPU per run)");
  cmd->add_flag("!--no-seat", options.seat, "do not bring pins and supports into contact before loading");
  cmd->add_option("--machine-compliance", model.machine_compliance,
                  "load-frame compliance C in m/N added to the simulated displacement (w + C F)");
  cmd->add_flag("--judge-fracture", options.judge_fracture,
                "let crack position and fragment sizes enter the verdict and the residual (always reported)");
  cmd->add_option_function<std::string>(
      "--score-reference",
      [&options](const std::string& name) { options.score_reference = measure::parse_score_reference(name); },
      "reference distribution of each residual component: normal (the raw score as N(0, 1), default) or welch "
      "(Student t with the Welch-Satterthwaite degrees of freedom of its estimated variances, converted to the "
      "normal score of equal tail probability)")
      ->check(CLI::IsMember({"normal", "welch"}));
  cmd->add_flag("!--ignore-geometry", options.check_geometry,
                "compare even when the specimens' span or pin distance differ from the scene's");
  cmd->add_option("--time-compression", options.time_compression,
                  "simulate each specimen at this factor times its measured loading rate (quasi-static surrogate; "
                  "model times and bond.viscosity_time are then this factor shorter than the lab's)")
      ->check(CLI::PositiveNumber);
}

CompareOptions compare_options(const SimulationOptions& options) {
  CompareOptions c;
  c.judge_fracture = options.judge_fracture;
  c.score_reference = options.score_reference;
  return c;
}

EnsembleSimulator::EnsembleSimulator(const SimulationOptions& options, const std::vector<fs::path>& plugin_dirs)
    : options_(options), plugin_dirs_(plugin_dirs), pool_(options.work_dir, plugin_dirs, options.workers) {
  if (options_.isolate) pool_.isolate_runs(shard_run_worker());
}

std::vector<std::vector<Specimen>> EnsembleSimulator::simulate(const std::vector<ModelPlan>& models, std::ostream& log) {
  std::vector<RunRequest> requests;
  for (const auto& m : models) {
    SceneOverrides overrides = m.overrides;
    const double rate = m.loading_rate * options_.time_compression;
    if (rate > 0 && !rate_hint_given_) {
      rate_hint_given_ = true;
      const double own = pool_.fixture().scene_rate(m.scene, m.overrides);
      if (options_.time_compression != 1)
        log << fmt::format("time compression {0:g}: the model loads at {1:g} m/s for data at {2:g} m/s; model times "
                           "(and bond.viscosity_time) are the lab's divided by {0:g}\n",
                           options_.time_compression, rate, m.loading_rate);
      else if (own > 0 && rate < 0.5 * own)
        log << fmt::format("note: the data are at {:g} m/s, {:.3g} x slower than the scene's {:g} m/s, and the model runs at "
                           "the data's rate ({:.3g} x the scene's run time). If the scene is quasi-static at its own rate "
                           "(shard bending-rate-check), --time-compression {:.3g} runs it there\n",
                           m.loading_rate, own / rate, own, own / rate, own / rate);
    }
    if (rate > 0) {
      for (auto& r : pool_.fixture().rate_overrides(m.scene, m.overrides, rate)) overrides.push_back(std::move(r));
      const double own = pool_.fixture().scene_rate(m.scene, m.overrides);
      if (own > 0 && rate / own > max_rate_factor_) max_rate_factor_ = rate / own, fastest_rate_ = rate, scene_rate_ = own;
    }
    // The lab's ramp in model time: the model's times are the lab's divided by the compression.
    if (!test_.ramp.empty())
      for (auto& r : pool_.fixture().ramp_overrides(m.scene, m.overrides, test_.ramp, test_.ramp_time / options_.time_compression))
        overrides.push_back(std::move(r));
    for (int k = 0; k < options_.seeds; ++k) requests.push_back({m.scene, overrides, options_.first_seed + k, options_.seat});
  }
  const auto results = pool_.run(requests, log);
  std::vector<std::vector<Specimen>> out(models.size());
  std::size_t i = 0;
  for (std::size_t m = 0; m < models.size(); ++m)
    for (int k = 0; k < options_.seeds; ++k, ++i) {
      Specimen s;
      s.id = fmt::format("sim_seed{}", options_.first_seed + k);
      s.curve = results[i].curve;
      s.curve.id = fmt::format("{} (run {})", s.id, results[i].key);  // what a message about the curve names
      s.crack_position = results[i].crack_position;
      s.fragment_sizes = results[i].fragment_sizes;
      s = recorded_as_tested(std::move(s), models[m], test_,
                             fmt::format("the simulated curve of {} (seed {}, run {})", models[m].scene.string(),
                                         options_.first_seed + k, results[i].key));
      (models[m].probe ? max_probe_ke_ : max_ke_) = std::max(models[m].probe ? max_probe_ke_ : max_ke_,
                                                             results[i].kinetic_to_elastic);
      out[m].push_back(std::move(s));
    }
  return out;
}

std::string EnsembleSimulator::dynamic_warning() const {
  const bool energetic = max_ke_ > kDynamicKineticToElastic;
  const bool fast = max_rate_factor_ > 1.01;
  if (!energetic && !fast) return {};
  // Only the energy ratio shows inertia; a rate above the checked one alone means it is unverified.
  std::string w = fmt::format("the model {} dynamic at the data's rate: kinetic/elastic energy {:.2g} before breakage "
                              "({} the quasi-static bound {:g})",
                              energetic ? "is" : "may be", max_ke_, energetic ? "above" : "below",
                              kDynamicKineticToElastic);
  if (fast)
    w += fmt::format("; the model runs at {:.3g} mm/s (the data's rate x time compression {:g}), {:.3g}x faster than "
                     "the {:.3g} mm/s the scene was checked at",
                     1e3 * fastest_rate_, options_.time_compression, max_rate_factor_, 1e3 * scene_rate_);
  return w + ". Inertial forces enter the simulated curve: lower --time-compression, or check the scene at this rate "
             "(shard bending-rate-check --set on its pin velocities)";
}

void EnsembleSimulator::check_inputs(const ModelPlan& model, const std::vector<Specimen>& specimens, const Metadata& metadata) {
  if (inputs_checked_ || specimens.empty()) return;
  inputs_checked_ = true;
  use_test_conditions(metadata.test);
  if (options_.seeds < 2)
    fmt::print(stderr,
               "warning: one packing seed: the model's packing-to-packing scatter is unknown, so the scores below count "
               "the measurement's noise only and read far beyond noise (use --seeds 3 or more)\n");
  if (!options_.check_geometry) return;
  const SpecimenSetup scene = pool_.fixture().specimen_setup(model.scene, model.overrides, options_.first_seed);
  auto off = [](double measured, double simulated) { return std::abs(measured - simulated) > 0.02 * simulated; };
  for (const auto& s : specimens)
    if (off(s.span, scene.span) || off(s.pin_distance, scene.pin_distance))
      throw std::runtime_error(fmt::format(
          "specimen {}: span {:.4g} mm and pin distance {:.4g} mm, but the model scene {} has span {:.4g} mm and pin "
          "distance {:.4g} mm (specimen {:.4g} x {:.4g} x {:.4g} mm). Make a scene of the measured set-up (move its "
          "support and pin walls, size its body), or pass --ignore-geometry to compare anyway",
          s.id, 1e3 * s.span, 1e3 * s.pin_distance, model.scene.string(), 1e3 * scene.span, 1e3 * scene.pin_distance,
          1e3 * scene.length, 1e3 * scene.width, 1e3 * scene.height));
  // A packing's extent across and along the load is the spheres' reach: it differs from seed to
  // seed (and from the nominal box) by up to one diameter.
  auto off_section = [&](double measured, double simulated) {
    return std::abs(measured - simulated) > std::max(0.02 * simulated, scene.particle_diameter);
  };
  for (const auto& s : specimens)
    if (off_section(s.width, scene.width) || off_section(s.height, scene.height))
      throw std::runtime_error(fmt::format(
          "specimen {}: width {:.4g} mm and height {:.4g} mm, but the model scene {} has a body {:.4g} mm wide and "
          "{:.4g} mm high (more than 2 % and one particle diameter, {:.3g} mm, apart). Size the scene's body to the "
          "measured specimens, or pass --ignore-geometry to compare anyway",
          s.id, 1e3 * s.width, 1e3 * s.height, model.scene.string(), 1e3 * scene.width, 1e3 * scene.height,
          1e3 * scene.particle_diameter));
}

void EnsembleSimulator::check_model(const ModelPlan& model) {
  pool_.fixture().specimen_setup(model.scene, model.overrides, options_.first_seed);
}

ParameterRange EnsembleSimulator::parameter_range(const std::string& key) const {
  return plugin_parameter_range(key, plugin_dirs_);
}

RunHealth EnsembleSimulator::health() const { return {max_ke_, max_probe_ke_, dynamic_warning()}; }

std::vector<RateComparison> simulate_and_compare(EnsembleSimulator& simulator, const RateGroups& groups, const Metadata& metadata,
                                                 const std::vector<ModelPlan>& models, std::ostream& log) {
  return measure::simulate_and_compare(simulator, {groups, metadata, compare_options(simulator.options())}, models, log);
}

}  // namespace shard
