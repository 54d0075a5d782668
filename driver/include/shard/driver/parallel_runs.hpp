#pragma once
// Many independent runs in one process: `workers` threads take the runs in order, one at a time
// each. A run that throws (bad input, a numerical blow-up caught by the health watch, a write
// error) is reported as failed with its message and the others go on; a crash of the process
// itself (a segmentation fault in a plugin) is not caught, as no thread can survive it.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace shard::driver {

// Calls run(i) for i in [0, count) on min(workers, count) threads (at least one). After each run,
// done(i, error) is called with error empty on success, else the exception's message; done calls
// are serialised (a lock), so they may log and write shared files. Returns the errors by index.
// Each run should use one OpenMP thread (RunSpec::threads = 1): the workers are the parallelism.
std::vector<std::string> run_in_parallel(std::size_t count, int workers, const std::function<void(std::size_t)>& run,
                                         const std::function<void(std::size_t, const std::string&)>& done = {});

// How many of `count` runs that write their run files from threads of this process may go at
// once: `workers`, or 1 when the HDF5 library is not thread-safe (run_files_thread_safe: the MPI
// build's crashes in H5Dwrite when two runs write at once). Runs in worker processes are not
// limited by it.
int in_process_workers(int workers, std::size_t count);

}  // namespace shard::driver
