#pragma once
// What the measurement commands share: a model (scene + overrides + machine compliance), its
// packing-seed replicates run through the RunPool, and the options every command takes.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "measure_runner.hpp"
#include "shard/measure/comparison.hpp"
#include "shard/measure/measurements.hpp"
#include "shard/measure/model_plan.hpp"
#include "shard/measure/rate_comparison.hpp"
#include "shard/measure/rate_groups.hpp"
#include "shard/measure/simulator.hpp"
#include "shard/scene_override.hpp"

namespace shard {

using measure::ModelPlan;
using measure::scene_number;
using measure::with_effect;
using measure::with_effects;
using measure::with_parameters;

struct SimulationOptions {
  int seeds = 3;
  long first_seed = 1;
  std::filesystem::path work_dir = "shard_work";
  int workers = 2;
  // Each run in a worker process of its own (`shard run-worker`), so a crash in a plugin fails
  // that run and not the command. Off by default: a worker's start and plugin loading cost
  // 0.3-0.4 s of CPU per run, half a tiny-beam run (docs/reference/driver.md, "Isolated runs").
  bool isolate = false;
  bool seat = true;
  // The model runs each specimen at this factor times its measured loading rate. Explicit DEM
  // cannot afford a lab's 0.2 mm/s on a resolved beam; a quasi-static model gives the same
  // force-displacement curve at a faster rate (check with `shard bending-rate-check`), and the
  // curves are compared against displacement, not time. The model's times, and its rate
  // parameters (bond.viscosity_time), are then this factor shorter than the lab's.
  double time_compression = 1;
  // The specimens' span and pin distance must be the scene's (2 %): a model of another test
  // geometry is not a model of these data.
  bool check_geometry = true;
  bool judge_fracture = false;  // CompareOptions::judge_fracture
  measure::ScoreReference score_reference = measure::ScoreReference::Normal;  // CompareOptions::score_reference
};

void add_simulation_options(CLI::App* cmd, ModelPlan& model, SimulationOptions& options);
// How the command's options score each residual component (--judge-fracture, --score-reference).
measure::CompareOptions compare_options(const SimulationOptions& options);

// The DEM ensemble as the measurement science's simulator: every model's packing-seed replicates
// run through the RunPool (cached, on threads, worker processes or MPI ranks), at the data's rate
// and ramp, recorded as the lab recorded.
class EnsembleSimulator final : public measure::Simulator {
 public:
  EnsembleSimulator(const SimulationOptions& options, const std::vector<std::filesystem::path>& plugin_dirs);
  // The replicates of every model, all runs in one parallel batch.
  std::vector<std::vector<measure::Specimen>> simulate(const std::vector<ModelPlan>& models, std::ostream& log) override;
  std::vector<measure::Specimen> simulate(const ModelPlan& model, std::ostream& log) { return simulate_one(model, log); }
  void check_model(const ModelPlan& model) override;
  double parameter(const ModelPlan& model, const std::string& key) const override { return scene_number(model, key); }
  measure::ParameterRange parameter_range(const std::string& key) const override;
  measure::RunHealth health() const override;
  RunPool& pool() { return pool_; }
  const SimulationOptions& options() const { return options_; }
  // Largest kinetic/elastic ratio of the runs simulated so far (the quasi-static check).
  double max_kinetic_to_elastic() const { return max_ke_; }
  // The same over the probes (ModelPlan::probe), which the warning does not judge.
  double max_probe_kinetic_to_elastic() const { return max_probe_ke_; }
  // Largest ratio of a run's pin speed to the scene's own (the rate it was checked quasi-static
  // at with `shard bending-rate-check`); 1 when every run was at the scene's rate or slower.
  double max_rate_over_scene() const { return max_rate_factor_; }
  // Empty while the runs are quasi-static; otherwise the warning, in the field's words, that the
  // model is dynamic at the data's rate (kinetic/elastic above kDynamicKineticToElastic, or runs
  // faster than the scene's own rate): inertial forces enter the simulated curve.
  std::string dynamic_warning() const;
  // Run the pins as the lab did ([test] ramp, scaled by the time compression), record the curves
  // as it did (zeroed at the seating preload) and count fragments as it did (no smaller than
  // the fragment-size threshold). check_inputs sets them from the data's metadata.
  void use_test_conditions(const measure::TestConditions& test) { test_ = test; }
  const measure::TestConditions& test_conditions() const { return test_; }
  // Before the first simulation of a command (later calls do nothing: its models share the scene
  // and the data): takes the data's test conditions, warns when one packing seed leaves the
  // model's scatter unknown, and throws, naming both, when a specimen's span or pin distance
  // differs from the scene's by more than 2 %, or its width or height by more than 2 % and one
  // particle diameter (a packing's extent differs from seed to seed by up to a diameter).
  void check_inputs(const ModelPlan& model, const std::vector<measure::Specimen>& specimens,
                    const measure::Metadata& metadata) override;

 private:
  SimulationOptions options_;
  std::vector<std::filesystem::path> plugin_dirs_;
  RunPool pool_;
  double max_ke_ = 0;
  double max_probe_ke_ = 0;
  double max_rate_factor_ = 1;
  double fastest_rate_ = 0, scene_rate_ = 0;  // m/s, of the run with max_rate_factor_
  measure::TestConditions test_;
  bool rate_hint_given_ = false;
  bool inputs_checked_ = false;
};

using measure::RateGroups;
using measure::rate_groups;
using measure::specimens_at_rate;

using measure::RateComparison;

// Simulates every model at every rate of `groups` (one parallel batch) and compares, scored as the
// command's options ask (measure::simulate_and_compare).
std::vector<RateComparison> simulate_and_compare(EnsembleSimulator& simulator, const RateGroups& groups,
                                                 const measure::Metadata& metadata, const std::vector<ModelPlan>& models,
                                                 std::ostream& log);

}  // namespace shard
