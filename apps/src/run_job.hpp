#pragma once
// One simulation of the measurement loop as a job that can run anywhere: on a thread of this
// process, in a worker process (`shard run-worker`, a crash there ends that process only), or on
// another MPI rank. The job and its outcome travel as binary records (byte_record.hpp), never as
// printed text: the curve arrives bit for bit.
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "shard/driver/worker_process.hpp"
#include "shard/scene_override.hpp"

namespace shard {

class PluginHost;

struct RunJob {
  std::string key;                  // the run cache's key (of the resolved scene text)
  std::filesystem::path scene;
  SceneOverrides overrides;         // all of them: seed and seating included
  std::filesystem::path out_dir;    // its run folder, removed when the run has been read
  std::vector<std::filesystem::path> plugin_dirs;  // --plugin-dir of the command
  bool isolated = false;            // on another MPI rank: run it there in a worker process
};

// What the loop keeps of a run: the load-displacement curve, the quasi-static check and the
// fracture (shard::bending's analysis of the run file).
struct RunOutcome {
  std::vector<double> time, displacement, load;
  double kinetic_to_elastic = 0;  // max before breakage
  double wall_seconds = 0;
  bool fracture_analysed = false;  // false: not a four-point bending run
  double crack_position = std::numeric_limits<double>::quiet_NaN();  // m from the centre; NaN: no crack
  std::vector<double> fragment_sizes;                                // equivalent diameters, m
  std::string failure;  // set by a worker whose run threw; empty: it ran
};

// Runs the job here, on the calling thread with one OpenMP thread; throws what the run throws.
RunOutcome execute_run_job(const RunJob& job, const PluginHost& host);

// Runs the job in a worker process started by `worker`; throws (with the signal's name when one
// ended it) when the run failed or the worker died.
RunOutcome execute_run_job_isolated(const RunJob& job, const driver::WorkerCommand& worker);

// This program as a worker: /proc/self/exe with the hidden `run-worker` sub-command.
driver::WorkerCommand shard_run_worker();

// The body of `shard run-worker`: reads one job record from standard input, runs it, writes its
// outcome record (failure set when the run threw) to standard output. Anything else the run
// prints goes to standard error, so the record is all that standard output carries.
int serve_run_job(const std::vector<std::filesystem::path>& extra_plugin_dirs);

// Runs one encoded job here (or in a worker process when it says `isolated`) and returns its
// encoded outcome, a failure included: what another MPI rank does with each job it is sent.
std::string run_encoded_job(std::string_view job_record);

std::string encode_job(const RunJob& job);
RunJob decode_job(std::string_view record);
std::string encode_outcome(const RunOutcome& outcome);
RunOutcome decode_outcome(std::string_view record);

}  // namespace shard
