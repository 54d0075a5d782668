#pragma once
// One simulation of the measurement loop as a job that can run anywhere: on a thread of this
// process, in a worker process (`shard run-worker`, a crash there ends that process only), or on
// another MPI rank. The job and its outcome travel as binary records (byte_record.hpp), never as
// printed text: the curve arrives bit for bit.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "shard/analysis/load_curve.hpp"
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

// What the measurement loop keeps of a run: the load-displacement curve, the quasi-static check
// and the fracture (shard::bending's analysis of the run file). A worker sends it as a record
// (encode_outcome), the run cache keeps that record (run_cache.hpp), and the pool returns it.
struct RunOutcome {
  analysis::LoadCurve curve;  // uncertainties zero: a simulated curve has no measurement noise
  double kinetic_to_elastic = 0;  // max before breakage (quasi-static check)
  double wall_seconds = 0;        // of the run itself
  // The crack's distance from the centre between the pins along the beam, and every fragment's
  // equivalent diameter. Unset / empty when the run is not a four-point bending test or no bond broke.
  std::optional<double> crack_position;
  std::vector<double> fragment_sizes;
  std::string failure;  // why the run failed (empty: it ran)
  // Set by the pool, not recorded: the run cache's key, and whether the run was found there.
  std::string key;
  bool cached = false;
  bool failed() const { return !failure.empty(); }
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
