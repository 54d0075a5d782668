#pragma once
// The pieces of the run loop that the serial driver (run_driver.cpp) and the decomposed one
// (mpi/distributed_run.cpp) share: what a checkpoint carries of the loop, the run file's
// metadata, and the closing figures.
#include <string>
#include <vector>

#include "shard/checkpoint.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/output.hpp"
#include "shard/scene.hpp"

namespace shard::driver::detail {

// The loop's counters and curve; `health` is the energy watch's state (NumericalHealth::state),
// restored by the caller from the array "health".
void save_loop_state(Checkpoint& c, const RunResult& r, int frames_written, const std::vector<double>& health);
void restore_loop_state(const Checkpoint& c, RunResult& r, int& frames_written);
bool explicitly_sets_breakage(const std::string& scene_text);
RunMetadata run_metadata(const Scene& scene, const SceneInstance& inst, const PluginHost& host, const RunLog& log);
double kinetic_to_elastic_up_to_peak(const RunResult& r);

}  // namespace shard::driver::detail
