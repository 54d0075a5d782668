#pragma once
// `shard run`: a scene from file to run.h5, with a progress line and a stop rule.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace shard {

class Simulation;

struct RunOptions {
  std::filesystem::path scene;
  std::vector<std::string> overrides;  // --set section.key=value
  std::filesystem::path out_dir = ".";
  std::vector<std::filesystem::path> plugin_dirs;
  int threads = 0;  // 0: OpenMP default
  bool quiet = false;
  // --restart run.h5: continue the run in that file from its checkpoint (run.checkpoint.h5);
  // `scene` and `overrides` are then ignored (the run file holds the resolved scene).
  std::filesystem::path restart;
  int checkpoint_every = 1;            // frames between checkpoints; 0: only when stopping
  int health_every = 10;               // steps between checks for a numerical blow-up
  std::int64_t interrupt_at_step = -1;  // >= 0: behave as if SIGINT arrived at that step (tests)
};

struct RunSummary {
  std::filesystem::path output;
  std::int64_t steps = 0;
  double time = 0;
  double dt = 0;
  std::size_t particles = 0;
  std::size_t bonds_initial = 0;
  std::int64_t bonds_broken = 0;
  double peak_load = 0;                 // N, on the load walls along the loading direction
  double displacement_at_peak = 0;      // m
  double final_displacement = 0;        // m
  double wall_seconds = 0;
  std::string stop_reason;
  std::vector<double> load, displacement, time_series;  // the load curve, one row per series row
  // Kinetic energy less the rigid-body motion's (shard/bending/deformation_kinetic.hpp) and
  // elastic (bond + contact) energy of the rows before the first bond broke.
  std::vector<double> kinetic_before_break, elastic_before_break;
  // Quasi-static check: the largest kinetic / elastic energy ratio over the rows before the first
  // break whose load is at least 20 % of the run's final peak load (the seating rows, where the
  // elastic energy is still near zero, say nothing about inertia in the test).
  double max_kinetic_to_elastic = 0;
  std::filesystem::path checkpoint;     // the last checkpoint written (empty: none)
  std::int64_t checkpoint_step = -1;
  bool interrupted = false;             // SIGINT: stopped after writing a checkpoint
  std::int64_t restarted_from = -1;     // the checkpoint step a --restart continued from
};

// Runs the scene; progress and log lines go to `log` (nothing when quiet).
RunSummary run_scene(const RunOptions& options, std::ostream& log);

// Loads plugins from --plugin-dir, $SHARD_PLUGIN_PATH, the build and the install tree.
class PluginHost;
void load_plugins(PluginHost& host, const std::vector<std::filesystem::path>& dirs, std::ostream& log);

}  // namespace shard
