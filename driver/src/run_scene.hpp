#pragma once
// One run of a scene over a backend (run_backend.hpp): the same set-up, observed step loop,
// output, checkpoints and restart whether the simulation is whole in this process or decomposed
// over MPI ranks. driver::run and driver::run_distributed are this with their backend.
#include <vector>

#include "run_backend.hpp"
#include "shard/driver/run_driver.hpp"

namespace shard::driver::detail {

// Collective over the backend's ranks. Throws as driver::run does.
RunResult run_scene(const RunSpec& spec, const PluginHost& host, const std::vector<RunObserver*>& observers,
                    const RunLog& log, RunBackend& backend);

}  // namespace shard::driver::detail
