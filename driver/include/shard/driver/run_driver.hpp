#pragma once
// One run of a scene, in-process: scene -> run file, with the observers the caller composed
// (run_observer.hpp; the stock ones are in observers.hpp). `shard run`, `shard calibrate` and the
// measurement loop's worker threads all call this.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "shard/driver/run_observer.hpp"
#include "shard/driver/run_result.hpp"
#include "shard/scene_override.hpp"

namespace shard {
class PluginHost;
}

namespace shard::driver {

struct RunSpec {
  std::filesystem::path scene;
  SceneOverrides overrides;  // typed (scene_override.hpp); applied in order
  std::filesystem::path out_dir = ".";
  // Continue the run file from its checkpoint (run.checkpoint.h5): `scene` is then ignored (the run
  // file holds the resolved scene) and `overrides` may change only simulation.duration and [stop]
  // keys (a run extended past its end, another stop rule). Needs a CheckpointWriter to go on
  // writing them.
  std::filesystem::path restart;
  int threads = 0;       // OpenMP threads of this run (on this thread); 0: OpenMP's default
  int health_every = 10;  // steps between checks for a numerical blow-up
};

// Where the driver's own lines go: `info` (scene size, time step, packing quality) and `warning`
// (a scene that asks for something it cannot have). Either may be empty.
struct RunLog {
  std::function<void(const std::string&)> info;
  std::function<void(const std::string&)> warning;
};

// Runs the scene to its end or a stop rule. Throws SceneError / OutputError / CheckpointError for
// bad input, NumericalError (numerical_health.hpp) for a blow-up; whatever the observers throw
// passes through.
RunResult run(const RunSpec& spec, const PluginHost& host, const std::vector<RunObserver*>& observers,
              const RunLog& log = {});

}  // namespace shard::driver
