#include "measure_runner.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "run_cache.hpp"
#include "run_job.hpp"
#include "shard/app/run_command.hpp"
#include "shard/driver/parallel_runs.hpp"
#if SHARD_MPI_ENSEMBLE
#include "shard/driver/rank_runs.hpp"
#endif
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"
#include "shard/measure/significant_digits.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

// "seed 3, with bond.x=1 wall.pin.velocity=[...]": the request as the user can repeat it.
std::string describe_request(const RunRequest& r) {
  std::string text = fmt::format("seed {}", r.seed);
  if (!r.overrides.empty()) {
    text += ", with";
    for (const auto& o : r.overrides) text += fmt::format(" {}", o.text());
  }
  return text;
}

}  // namespace

std::string fnv1a_hex(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : text) h = (h ^ ch) * 1099511628211ull;
  return fmt::format("{:016x}", h);
}

RunPool::RunPool(fs::path work_dir, std::vector<fs::path> plugin_dirs, int workers)
    : work_dir_(std::move(work_dir)),
      plugin_dirs_(std::move(plugin_dirs)),
      workers_(std::max(1, workers)),
      host_(std::make_unique<PluginHost>()),
      fixture_(std::make_unique<BendingFixture>(*host_)) {
  std::ostringstream quiet;
  load_plugins(*host_, plugin_dirs_, quiet);
}

RunPool::~RunPool() = default;

SceneOverrides RunPool::full_overrides(const RunRequest& request) const {
  SceneOverrides o = request.overrides;
  o.push_back({"simulation.seed", std::int64_t{request.seed}});
  return o;
}

SceneOverrides RunPool::run_overrides(const RunRequest& request) const {
  SceneOverrides o = full_overrides(request);
  if (request.seat)
    for (auto& s : fixture_->seating_overrides(request.scene, o)) o.push_back(std::move(s));
  return o;
}

std::string RunPool::resolved_text(const RunRequest& request) const {
  return load_scene(request.scene, *host_, run_overrides(request)).resolved_text;
}

std::vector<RunJob> RunPool::jobs_to_run(const std::vector<RunRequest>& requests, const RunCache& cache,
                                         std::vector<std::string>& keys, std::map<std::string, RunOutcome>& found,
                                         std::ostream& log) const {
  std::map<std::string, RunJob> pending;  // one job per distinct key
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const RunRequest& r = requests[i];
    SceneOverrides o = run_overrides(r);
    keys[i] = fnv1a_hex(load_scene(r.scene, *host_, o).resolved_text);
    if (found.count(keys[i]) || pending.count(keys[i])) continue;
    if (auto cached = cache.find(keys[i], log)) {
      found.emplace(keys[i], std::move(*cached));
      continue;
    }
    RunJob job;
    job.key = keys[i];
    job.scene = r.scene;
    job.overrides = std::move(o);
    job.out_dir = work_dir_ / "runs" / keys[i];
    job.plugin_dirs = plugin_dirs_;
    job.isolated = worker_.has_value();
    pending.emplace(keys[i], std::move(job));
  }
  std::vector<RunJob> queue;
  for (auto& [k, j] : pending) queue.push_back(std::move(j));
  return queue;
}

std::vector<RunOutcome> RunPool::try_run(const std::vector<RunRequest>& requests, std::ostream& log) {
  std::vector<std::string> keys(requests.size());
  std::map<std::string, RunOutcome> found;  // by key: the cached runs, then the runs made
  const RunCache cache(work_dir_ / "cache");
  const std::vector<RunJob> queue = jobs_to_run(requests, cache, keys, found, log);
  runs_started_ += queue.size();
  std::size_t done = 0;
  std::map<std::string, std::string> failures;  // key -> why
  // Each run's outcome as the cache keeps it: written by its own thread, read after its report.
  std::vector<RunOutcome> finished(queue.size());
  // A full disk or a file-size limit must surface as a write error, not kill the process.
  void (*previous_xfsz)(int) = std::signal(SIGXFSZ, SIG_IGN);
  auto report = [&](std::size_t j, const std::string& error) {
    if (!error.empty()) {
      failures[queue[j].key] = error;
      fmt::print(log, "  run {} of {} failed: {}\n", queue[j].key, queue[j].scene.string(),
                 error.substr(0, error.find('\n')));
      return;
    }
    ++done;
    fmt::print(log, "  run {}/{} done ({:.1f} s, kinetic/elastic {:.2g})\n", done, queue.size(),
               finished[j].wall_seconds, finished[j].kinetic_to_elastic);
    found.emplace(queue[j].key, std::move(finished[j]));
  };
#if SHARD_MPI_ENSEMBLE
  if (driver::ranks_available()) {
    // Rank 0 hands the runs out to the other ranks and writes their outcomes to the cache.
    if (!queue.empty())
      fmt::print(log, "  {} runs over {} MPI rank{}\n", queue.size(), driver::worker_rank_count(),
                 driver::worker_rank_count() > 1 ? "s" : "");
    driver::run_on_ranks(
        queue.size(), [&](std::size_t j) { return encode_job(queue[j]); },
        [&](std::size_t j, const std::string& record) {
          std::string error;
          try {
            const RunOutcome outcome = decode_outcome(record);
            if (!outcome.failure.empty()) error = outcome.failure;
            else finished[j] = cache.store(queue[j].key, outcome);
          } catch (const std::exception& e) {
            error = e.what();
          }
          report(j, error);
        });
    std::signal(SIGXFSZ, previous_xfsz);
    return collect(requests, keys, found, failures);
  }
#endif
  // One OpenMP thread per run, on its own thread or in its own worker process. Runs on threads of
  // this process write their run files at once, which an HDF5 library built without thread safety
  // does not survive (the MPI build's): there they go one at a time.
  auto run_one = [&](std::size_t j) {
    const RunJob& job = queue[j];
    finished[j] = cache.store(job.key, worker_ ? execute_run_job_isolated(job, *worker_) : execute_run_job(job, *host_));
  };
  const int at_once = worker_ ? workers_ : driver::in_process_workers(workers_, queue.size());
  if (at_once < workers_) {
    if (!warned_unsafe_hdf5_)
      fmt::print(log, "  note: this HDF5 library is not thread-safe (an MPI build's), so the runs go one at a time; "
                      "--isolate runs them in worker processes, mpirun on MPI ranks, {} at once\n", workers_);
    warned_unsafe_hdf5_ = true;
  }
  driver::run_in_parallel(queue.size(), at_once, run_one, report);
  std::signal(SIGXFSZ, previous_xfsz);
  return collect(requests, keys, found, failures);
}

std::vector<RunOutcome> RunPool::collect(const std::vector<RunRequest>& requests, const std::vector<std::string>& keys,
                                         const std::map<std::string, RunOutcome>& outcomes,
                                         const std::map<std::string, std::string>& failures) {
  std::vector<RunOutcome> results(requests.size());
  for (std::size_t i = 0; i < requests.size(); ++i) {
    if (const auto f = failures.find(keys[i]); f != failures.end()) {
      results[i].key = keys[i];
      results[i].failure = fmt::format("a simulation of {} ({}) failed: {}", requests[i].scene.string(),
                                       describe_request(requests[i]), f->second);
      continue;
    }
    results[i] = outcomes.at(keys[i]);
  }
  return results;
}

std::vector<RunOutcome> RunPool::run(const std::vector<RunRequest>& requests, std::ostream& log) {
  auto results = try_run(requests, log);
  for (const auto& r : results)
    if (r.failed()) throw std::runtime_error(r.failure);
  return results;
}

}  // namespace shard
