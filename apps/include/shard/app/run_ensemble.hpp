#pragma once
// Which commands an MPI ensemble spreads over its ranks (docs/how-to/run-on-a-cluster.md, "A
// measurement ensemble over ranks"): the measurement loop's (synth, compare, diagnose,
// calibrate-effect, ...), whose simulations are independent runs. Under `mpirun -np N shard COMMAND ...` in a build with
// SHARD_WITH_MPI, rank 0 runs such a command and ranks 1..N-1 run its simulations.
#include <string>
#include <vector>

namespace shard {

// True when `args` (argv after route_measurement_command) name such a command.
bool spreads_runs_over_ranks(const std::vector<std::string>& args);

}  // namespace shard
