#pragma once
// One job in a fresh process: a crash of the job (a segmentation fault in a plugin, an abort)
// ends that process only, and the caller is told which signal ended it.
//
// Why a new program image (posix_spawn + exec) rather than fork(): the caller is multithreaded
// (the run pool's threads, OpenMP's team), and a fork()ed child of such a process inherits locks
// held by threads that do not exist in it (malloc's, OpenMP's, HDF5's), so it may deadlock before
// it runs anything. posix_spawn starts the worker from a clean image, which also gives each run
// its own OpenMP runtime and HDF5 library state. The cost is the program's start and its plugin
// loading, once per run (docs/reference/driver.md, "Isolated runs", has the measured figure).
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace shard::driver {

// The program and arguments that run one job: the job arrives on its standard input, its
// result leaves on its standard output (both opaque bytes here), its standard error is the
// caller's.
struct WorkerCommand {
  std::filesystem::path executable;
  std::vector<std::string> arguments;
};

// A worker that ended without a result: killed by a signal (signal() != 0) or exited non-zero.
class WorkerDied : public std::runtime_error {
 public:
  WorkerDied(const std::string& what, int signal, int exit_code)
      : std::runtime_error(what), signal_(signal), exit_code_(exit_code) {}
  int signal() const { return signal_; }
  int exit_code() const { return exit_code_; }

 private:
  int signal_;
  int exit_code_;
};

// Starts `command`, writes `input` to its standard input and closes it, reads its standard output
// to the end and waits for it. Returns that output when the worker exits with status 0; throws
// WorkerDied when a signal ended it (naming the signal) or it exited otherwise, and
// std::runtime_error when it cannot be started. Safe to call from several threads at once.
std::string run_worker_process(const WorkerCommand& command, const std::string& input);

// "SIGSEGV (Segmentation fault)".
std::string describe_signal(int signal);

}  // namespace shard::driver
