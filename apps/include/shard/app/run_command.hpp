#pragma once
// `shard run`: a scene from file to run.h5, with a progress line and a stop rule. The run itself
// is the driver's (shard/driver/run_driver.hpp); this composes the observers a user's run has.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "shard/driver/run_result.hpp"
#include "shard/scene_override.hpp"

namespace shard {

struct RunOptions {
  std::filesystem::path scene;
  SceneOverrides overrides;  // --set section.key=value, parsed (SceneOverride::parse)
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
  // `shard run` under mpirun in a SHARD_WITH_MPI build: decompose the run over the job's ranks
  // (docs/explanation/scaling.md). Off for the commands that run scenes one after another.
  bool decompose_under_mpirun = false;
};

using RunSummary = driver::RunResult;

// Runs the scene with the stock observers: the scene's stop rules, Ctrl-C, checkpoints, fragment
// labels, the progress line (not when quiet), the closing lines and the curve CSV. Progress and
// log lines go to `log` (warnings even when quiet).
RunSummary run_scene(const RunOptions& options, std::ostream& log);

// Loads plugins from --plugin-dir, $SHARD_PLUGIN_PATH, the build and the install tree.
class PluginHost;
void load_plugins(PluginHost& host, const std::vector<std::filesystem::path>& dirs, std::ostream& log);

}  // namespace shard
