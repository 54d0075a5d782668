#pragma once
// Simulations for the measurement workflow (compare, synth, diagnose, calibrate-effect): each
// request (scene, overrides, packing seed) is resolved to its full scene text, looked up in a run
// cache keyed by that text, and otherwise run in-process through the run driver
// (shard/driver/run_driver.hpp), several at a time (one OpenMP thread each): on worker threads,
// or isolated, each in a worker process of its own (isolate_runs), or, in an MPI build started by
// mpirun, on the other ranks (docs/explanation/scaling.md). A run that fails (bad input, a numerical
// blow-up; with isolation also a crash, named by its signal) is reported as failed and the others
// go on. However they run, the runs' outcomes come back as records (run_job.hpp) and this process
// alone writes the cache (run_cache.hpp), so no two writers meet on a cache file.
//
// Seating: with `seat`, each run's fixture is seated on its packing (bending_fixture.hpp).
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bending_fixture.hpp"
#include "run_job.hpp"
#include "shard/driver/worker_process.hpp"
#include "shard/scene_override.hpp"

namespace shard {

class PluginHost;
class RunCache;

struct RunRequest {
  std::filesystem::path scene;
  SceneOverrides overrides;
  long seed = 1;
  bool seat = true;
};

class RunPool {
 public:
  RunPool(std::filesystem::path work_dir, std::vector<std::filesystem::path> plugin_dirs, int workers);
  ~RunPool();
  RunPool(const RunPool&) = delete;
  RunPool& operator=(const RunPool&) = delete;

  // The bending fixture of the pool's scenes (seating, specimen, rate and ramp overrides).
  const BendingFixture& fixture() const { return *fixture_; }
  // The full scene text a request runs (overrides, seed and seating applied).
  std::string resolved_text(const RunRequest& request) const;
  // Runs every request that is not cached, `workers` at a time on threads; results in the order
  // of the requests. A failed run leaves the others running (and cached); failed() is then set on
  // its result and `failure` says why.
  std::vector<RunOutcome> try_run(const std::vector<RunRequest>& requests, std::ostream& log);
  // The same, but throws (after every run ended) with the first failed run's message.
  std::vector<RunOutcome> run(const std::vector<RunRequest>& requests, std::ostream& log);

  // From now on each run goes to a worker process started by `worker` (shard_run_worker() in
  // run_job.hpp): a crash ends that run only. Without this call the runs are threads of this process.
  void isolate_runs(driver::WorkerCommand worker) { worker_ = std::move(worker); }
  bool isolated() const { return worker_.has_value(); }

  std::size_t runs_started() const { return runs_started_; }
  const std::filesystem::path& work_dir() const { return work_dir_; }

 private:
  SceneOverrides full_overrides(const RunRequest& request) const;  // with the packing seed
  SceneOverrides run_overrides(const RunRequest& request) const;   // and the seating, when asked
  // The jobs of the requests not in `cache`, one per distinct key; fills the requests' `keys` and
  // the cached outcomes by key (`found`).
  std::vector<RunJob> jobs_to_run(const std::vector<RunRequest>& requests, const RunCache& cache,
                                  std::vector<std::string>& keys, std::map<std::string, RunOutcome>& found,
                                  std::ostream& log) const;
  // The outcomes in the order of the requests: failed, or cached / run (`outcomes` by key).
  static std::vector<RunOutcome> collect(const std::vector<RunRequest>& requests, const std::vector<std::string>& keys,
                                         const std::map<std::string, RunOutcome>& outcomes,
                                         const std::map<std::string, std::string>& failures);

  std::filesystem::path work_dir_;
  std::vector<std::filesystem::path> plugin_dirs_;
  int workers_;
  std::unique_ptr<PluginHost> host_;
  std::unique_ptr<BendingFixture> fixture_;  // reads host_
  std::optional<driver::WorkerCommand> worker_;
  bool warned_unsafe_hdf5_ = false;  // the one-at-a-time note was printed
  std::size_t runs_started_ = 0;
};

// FNV-1a 64: a cache key that is the same in every build (std::hash need not be).
std::string fnv1a_hex(const std::string& text);

}  // namespace shard
