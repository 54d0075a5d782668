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
#include "shard/bending/test_setup.hpp"
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

// Offset s along the unit direction n at which a cylinder wall (axis a, radius R, centre p + s n)
// touches the sphere (x, r): the two roots of |(x - p - s n)_perp| = R + r. `first` is the smaller
// root (the wall arriving from -n), otherwise the larger one; NaN when the sphere is beside it.
double touch_offset(const Wall& w, const Vec3& n, const Vec3& x, double r, bool first) {
  const Vec3 a = w.axis.normalized();
  Vec3 d = x - w.point;
  if (std::abs(d.dot(a)) > 0.5 * w.length + r) return std::numeric_limits<double>::quiet_NaN();
  d -= d.dot(a) * a;
  const Vec3 n_perp = (n - n.dot(a) * a).normalized();
  const double along = d.dot(n_perp);
  const double lateral2 = (d - along * n_perp).squaredNorm();
  const double reach2 = (w.radius + r) * (w.radius + r);
  if (lateral2 >= reach2) return std::numeric_limits<double>::quiet_NaN();
  const double h = std::sqrt(reach2 - lateral2);
  return first ? along - h : along + h;
}

// A [stop] load wall: a loading pin of the test.
bool is_load_wall(const Scene& scene, const Wall& w) {
  return std::find(scene.stop.load_walls.begin(), scene.stop.load_walls.end(), w.name) != scene.stop.load_walls.end();
}

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
      host_(std::make_unique<PluginHost>()) {
  std::ostringstream quiet;
  load_plugins(*host_, plugin_dirs_, quiet);
}

RunPool::~RunPool() = default;

SceneOverrides RunPool::full_overrides(const RunRequest& request) const {
  SceneOverrides o = request.overrides;
  o.push_back({"simulation.seed", std::int64_t{request.seed}});
  return o;
}

SceneOverrides RunPool::seating_overrides(const RunRequest& request) const {
  const Scene scene = load_scene(request.scene, *host_, full_overrides(request));
  if (scene.stop.load_walls.empty()) return {};
  const Vec3 n = scene.stop.load_direction.normalized();
  const SceneInstance inst = instantiate(scene, *host_, [](const std::string&) {});
  const Particles& p = inst.simulation->particles();
  SceneOverrides out;
  for (const Wall& w : scene.walls) {
    if (w.shape != WallShape::Cylinder) continue;
    const bool loading = is_load_wall(scene, w);
    if (!loading && w.velocity.norm() > 0) continue;
    // A loading pin arrives along +n (first contact = smallest offset); a support waits on the far
    // side and is brought against the body along -n (largest offset).
    double best = loading ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double s = touch_offset(w, n, p.position[k], p.radius[k], loading);
      if (std::isnan(s)) continue;
      best = loading ? std::min(best, s) : std::max(best, s);
    }
    if (!std::isfinite(best)) continue;  // nothing under this cylinder: leave it where it is
    out.push_back({fmt::format("wall.{}.point", w.name), significant(Vec3(w.point + best * n), 12)});
  }
  return out;
}

SpecimenSetup RunPool::specimen_setup(const fs::path& scene_file, const SceneOverrides& overrides, long seed) const {
  RunRequest request{scene_file, overrides, seed, false};
  const Scene scene = load_scene(scene_file, *host_, full_overrides(request));
  std::vector<const Wall*> pins, supports;
  for (const Wall& w : scene.walls) {
    if (w.shape != WallShape::Cylinder) continue;
    if (is_load_wall(scene, w)) pins.push_back(&w);
    else if (w.velocity.norm() == 0) supports.push_back(&w);
  }
  if (pins.size() != 2 || supports.size() != 2)
    throw std::runtime_error(fmt::format(
        "{}: {} loading and {} resting cylinders; the specimen's span and pin distance are read from two of each "
        "(four-point bending). Give them explicitly (--length, --width, --height, --span, --pin-distance)",
        scene_file.string(), pins.size(), supports.size()));
  const bending::BeamFrame frame = bending::beam_frame(pins[0]->point, pins[1]->point, scene.stop.load_direction);
  const SceneInstance inst = instantiate(scene, *host_, [](const std::string&) {});
  const Particles& p = inst.simulation->particles();
  const bending::SphereExtent extent = bending::sphere_extent(frame, p.position, p.radius);
  SpecimenSetup s;
  s.pin_distance = bending::distance_along(frame, pins[0]->point, pins[1]->point);
  s.span = bending::distance_along(frame, supports[0]->point, supports[1]->point);
  s.length = extent.length, s.width = extent.width, s.height = extent.height;
  for (double r : p.radius) s.particle_diameter = std::max(s.particle_diameter, 2 * r);
  return s;
}

double RunPool::scene_rate(const fs::path& scene_file, const SceneOverrides& overrides) const {
  const Scene scene = load_scene(scene_file, *host_, overrides);
  double rate = 0;
  for (const Wall& w : scene.walls)
    if (is_load_wall(scene, w))
      rate = std::max(rate, w.velocity.norm());
  return rate;
}

SceneOverrides RunPool::rate_overrides(const fs::path& scene_file, const SceneOverrides& overrides, double rate) const {
  const Scene scene = load_scene(scene_file, *host_, overrides);
  const double own = scene_rate(scene_file, overrides);
  if (!(own > 0))
    throw std::runtime_error(fmt::format("{}: no moving [stop] load_walls, so the loading rate cannot be set to {} m/s",
                                         scene_file.string(), rate));
  if (std::abs(rate - own) <= 1e-9 * own) return {};
  const double f = rate / own;
  SceneOverrides out;
  for (const Wall& w : scene.walls)
    if (is_load_wall(scene, w)) {
      out.push_back({fmt::format("wall.{}.velocity", w.name), significant(Vec3(f * w.velocity), 12)});
      // The same ramp travel at the new speed: the ramp is f times shorter.
      if (w.motion.ramp != WallRamp::None)
        out.push_back({fmt::format("wall.{}.ramp_time", w.name), significant(w.motion.ramp_time / f, 12)});
    }
  out.push_back({"simulation.duration", significant(scene.duration / f, 12)});
  if (scene.series_interval > 0) out.push_back({"output.series_interval", significant(scene.series_interval / f, 12)});
  return out;
}

SceneOverrides RunPool::ramp_overrides(const fs::path& scene_file, const SceneOverrides& overrides,
                                       const std::string& ramp, double ramp_time) const {
  const Scene scene = load_scene(scene_file, *host_, overrides);
  SceneOverrides out;
  for (const Wall& w : scene.walls)
    if (is_load_wall(scene, w)) {
      out.push_back({fmt::format("wall.{}.ramp", w.name), ramp});
      // With ramp = "none" a ramp_time of the scene's is ignored (the loader allows that pair).
      if (ramp != "none") out.push_back({fmt::format("wall.{}.ramp_time", w.name), significant(ramp_time, 12)});
    }
  return out;
}

std::string RunPool::resolved_text(const RunRequest& request) const {
  SceneOverrides o = full_overrides(request);
  if (request.seat)
    for (auto& s : seating_overrides(request)) o.push_back(std::move(s));
  return load_scene(request.scene, *host_, o).resolved_text;
}

std::vector<RunJob> RunPool::jobs_to_run(const std::vector<RunRequest>& requests, const RunCache& cache,
                                         std::vector<std::string>& keys, std::map<std::string, RunOutcome>& found,
                                         std::ostream& log) const {
  std::map<std::string, RunJob> pending;  // one job per distinct key
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const RunRequest& r = requests[i];
    SceneOverrides o = full_overrides(r);
    if (r.seat)
      for (auto& s : seating_overrides(r)) o.push_back(std::move(s));
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
