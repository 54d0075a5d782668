// run_sweep: the (value, seed) runs of `shard sweep` on the run pool, each analysed per plate as
// `shard fragments --by-body` analyses it, then pooled (sweep_outputs.cpp writes the results).
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <mutex>
#include <ostream>
#include <set>
#include <thread>

#include "shard/analysis/run_tables.hpp"
#include "shard/run_file.hpp"
#include "shard/app/run_command.hpp"
#include "shard/app/sweep_command.hpp"
#include "shard/driver/scene_rules.hpp"
#include "shard/driver/parallel_runs.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"
#include "sweep_outputs.hpp"
#include "sweep_plan.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string duration_text(double seconds) {
  if (seconds < 90) return fmt::format("{:.0f} s", seconds);
  const auto minutes = static_cast<long>(seconds / 60);
  return fmt::format("{} min {:02.0f} s", minutes, seconds - 60.0 * static_cast<double>(minutes));
}

void check_options(const SweepOptions& o) {
  if (o.seeds < 1) throw SceneError(fmt::format("--seeds {}: at least one packing seed per value", o.seeds));
  if (o.workers < 0) throw SceneError(fmt::format("--workers {}: at least 1 (leave it out to use every core)", o.workers));
  if (!(o.intact_fraction > 0 && o.intact_fraction <= 1))
    throw SceneError(fmt::format("--intact-fraction {}: must lie in (0, 1]", o.intact_fraction));
  if (o.speed_bins > 0 && !o.speed_edges.empty()) throw SceneError("give either --speed-bins or --speed-edges, not both");
  for (std::size_t e = 1; e < o.speed_edges.size(); ++e)
    if (!(o.speed_edges[e] > o.speed_edges[e - 1]))
      throw SceneError(fmt::format("--speed-edges must ascend: {} follows {}", o.speed_edges[e], o.speed_edges[e - 1]));
  if (!fs::is_regular_file(o.scene)) throw SceneError(fmt::format("{}: no such scene file", o.scene.string()));
}

// The runs, value-major, then seed.
std::vector<SweepRun> planned_runs(const VarySpec& vary, std::int64_t seeds) {
  std::vector<SweepRun> runs;
  for (double v : vary.values)
    for (std::int64_t s = 0; s < seeds; ++s) {
      SweepRun r;
      r.value = v;
      r.seed = s;
      r.label = fmt::format("v{:g}_s{}", v, s);
      runs.push_back(r);
    }
  return runs;
}

// A run that ended: its plates analysed as `shard fragments --by-body` does, the table written
// into its file (/bodies/<k>); a failure to analyse becomes the run's error.
void analyse_plates(SweepRun& r, const SweepOptions& options, std::vector<analysis::PlateOutcome>& plates) {
  try {
    RunFile file(r.run_file, RunFile::Mode::read_write);
    const analysis::RunBodies bodies =
        analysis::analyse_run_bodies(file, std::nullopt, options.intact_fraction, options.fines_size);
    analysis::write_body_table(file, static_cast<std::size_t>(bodies.frame), bodies.report);
    plates = analysis::plate_outcomes(bodies.report, bodies.fragments, r.label, r.value, r.seed);
    r.plates = bodies.report.bodies.size();
    r.broken = bodies.report.broken;
    r.x50 = bodies.report.pooled.x50;
  } catch (const std::exception& e) {
    r.error = fmt::format("the run ended but its plates could not be analysed: {}", e.what());
  }
}

// One line a finished run: how far the sweep is, the run's plates, the breakage so far, the ETA.
class SweepProgress {
 public:
  SweepProgress(std::size_t count, const std::string& value_name, std::ostream& log)
      : count_(count), value_name_(value_name), log_(log) {}
  void finished(const SweepRun& r) {
    ++finished_;
    failed_ += r.failed();
    plates_ += r.plates;
    broken_ += r.broken;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const double eta = elapsed / static_cast<double>(finished_) * static_cast<double>(count_ - finished_);
    const std::string this_run =
        r.failed() ? fmt::format("FAILED: {}", r.error.substr(0, r.error.find('\n')))
                   : fmt::format("{} plates, {} broken, {:.1f} s", r.plates, r.broken, r.wall_seconds);
    const std::string share =
        plates_ > 0 ? fmt::format(" ({:.0f} %)", 100.0 * static_cast<double>(broken_) / static_cast<double>(plates_)) : "";
    fmt::print(log_, "sweep: {}/{} runs{} | {} = {:g}, seed {}: {} | so far {} plates, {} broken{} | {} elapsed{}\n",
               finished_, count_, failed_ > 0 ? fmt::format(" ({} failed)", failed_) : "", value_name_, r.value, r.seed,
               this_run, plates_, broken_, share, duration_text(elapsed),
               finished_ < count_ ? fmt::format(", ETA {}", duration_text(eta)) : "");
  }

 private:
  std::size_t count_, finished_ = 0, failed_ = 0, plates_ = 0, broken_ = 0;
  std::string value_name_;
  std::ostream& log_;
  Clock::time_point start_ = Clock::now();
};

// A full disk or a file-size limit must surface as a write error, not kill the process: SIGXFSZ
// ignored while the runs write, restored however the sweep ends.
class FileSizeSignalIgnored {
 public:
  FileSizeSignalIgnored() : previous_(std::signal(SIGXFSZ, SIG_IGN)) {}
  ~FileSizeSignalIgnored() { std::signal(SIGXFSZ, previous_); }
  FileSizeSignalIgnored(const FileSizeSignalIgnored&) = delete;
  FileSizeSignalIgnored& operator=(const FileSizeSignalIgnored&) = delete;

 private:
  void (*previous_)(int);
};

// Pooled over the runs that ran: per plate, by impact speed and by swept value.
void pool_plates(const SweepOptions& options, std::vector<std::vector<analysis::PlateOutcome>>& plates,
                 SweepResult& result) {
  for (auto& p : plates) result.plates.insert(result.plates.end(), p.begin(), p.end());
  const analysis::CurveOptions curve;
  result.speed_edges = options.speed_edges.empty() ? analysis::speed_bin_edges(result.plates, options.speed_bins)
                                                   : options.speed_edges;
  result.by_speed = analysis::breakage_by_speed(result.plates, result.speed_edges, curve);
  result.by_value = analysis::breakage_by_value(result.plates, curve);
}

}  // namespace

std::size_t SweepResult::failed() const {
  return static_cast<std::size_t>(std::count_if(runs.begin(), runs.end(), [](const SweepRun& r) { return r.failed(); }));
}

SweepResult run_sweep(const SweepOptions& options, std::ostream& log) {
  check_options(options);
  const VarySpec vary = parse_vary(options.vary);
  const SceneOverrides base = parse_overrides(options.sets);
  PluginHost host;
  load_plugins(host, options.plugin_dirs, log);
  const SweepPlan plan = plan_sweep(options.scene, base, vary, host);

  SweepResult result;
  result.value_label = plan.value_label;
  result.runs = planned_runs(vary, options.seeds);
  const std::size_t count = result.runs.size();
  const int workers = options.workers > 0 ? options.workers
                                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  fs::create_directories(options.out / "runs");
  if (!options.quiet)
    fmt::print(log, "sweep: {} runs ({} values of {} x {} seed{}) of {} on {} worker{} -> {}\n", count,
               vary.values.size(), plan.value_label, options.seeds, options.seeds == 1 ? "" : "s",
               options.scene.string(), std::min<std::size_t>(static_cast<std::size_t>(workers), count),
               workers == 1 ? "" : "s", options.out.string());

  // Written by run_one(i) for its own index only, read after it reported.
  std::vector<fs::path> outputs(count);
  std::vector<double> walls(count, 0.0);
  std::vector<std::vector<analysis::PlateOutcome>> plates(count);
  std::mutex warnings_lock;
  std::set<std::string> warnings_seen;
  auto warn = [&](const std::string& text) {
    const std::lock_guard lock(warnings_lock);
    if (warnings_seen.insert(text).second) fmt::print(log, "warning: {}\n", text);
  };
  auto run_one = [&](std::size_t i) {
    const SweepRun& r = result.runs[i];
    driver::RunSpec spec;
    spec.scene = options.scene;
    spec.overrides = run_overrides(plan, base, r.value, r.seed);
    spec.out_dir = options.out / "runs" / r.label;
    spec.threads = 1;
    std::error_code ignored;
    fs::remove_all(spec.out_dir, ignored);  // an earlier sweep's run of this label
    driver::SceneRules scene_rules;
    const driver::RunResult rr = driver::run(spec, host, scene_rules.observers(), driver::RunLog{{}, warn});
    outputs[i] = rr.output;
    walls[i] = rr.wall_seconds;
  };
  SweepProgress progress(count, plan.value_name, log);
  auto done = [&](std::size_t i, const std::string& error) {
    SweepRun& r = result.runs[i];
    r.error = error;
    if (r.error.empty()) {
      r.run_file = outputs[i];
      r.wall_seconds = walls[i];
      analyse_plates(r, options, plates[i]);
    }
    if (!options.quiet) progress.finished(r);
  };
  // An HDF5 library without thread safety (the MPI build's) crashes when two runs write at once.
  const int at_once = driver::in_process_workers(workers, count);
  if (at_once < workers)
    fmt::print(log, "note: this HDF5 library is not thread-safe (an MPI build's), so the sweep's runs go one at a "
                    "time\n");
  const auto start = Clock::now();
  {
    const FileSizeSignalIgnored writes_may_fail;
    driver::run_in_parallel(count, at_once, run_one, done);
  }
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  pool_plates(options, plates, result);
  write_sweep_outputs(options, plan, result, analysis::CurveOptions{}, log);
  return result;
}

}  // namespace shard
