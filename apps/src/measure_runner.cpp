#include "measure_runner.hpp"

#include <fmt/format.h>
#include <fmt/os.h>
#include <fmt/ostream.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "shard/app/run_command.hpp"
#include "shard/bending/bending_run.hpp"
#include "shard/bending/test_setup.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

extern char** environ;

namespace shard {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

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

struct Child {
  pid_t pid = -1;
  std::size_t job = 0;
  fs::path dir;
  std::chrono::steady_clock::time_point start;
};

double log_number(const std::string& log, const std::string& before, double fallback) {
  const auto at = log.rfind(before);
  if (at == std::string::npos) return fallback;
  try {
    return std::stod(log.substr(at + before.size()));
  } catch (const std::exception&) {
    return fallback;
  }
}

// The curve a run wrote (time_s, displacement_m, force_N), with comment lines skipped.
measure::Curve read_run_curve(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("cannot read the run's curve {}", file.string()));
  measure::Curve c;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    double t = 0, w = 0, f = 0;
    char c1 = 0, c2 = 0;
    std::istringstream row(line);
    if (!(row >> t >> c1 >> w >> c2 >> f)) throw std::runtime_error(fmt::format("{}: unreadable row '{}'", file.string(), line));
    c.time.push_back(t);
    c.displacement.push_back(w);
    c.force.push_back(f);
  }
  c.u_force.assign(c.size(), 0.0);
  c.u_displacement.assign(c.size(), 0.0);
  return c;
}

// <key>.fracture.csv beside a cached curve: "# crack_position=<m or nan>", then one fragment
// size (m) per line.
void write_fracture(const fs::path& run, const fs::path& file) {
  bending::BendingReport report;
  try {
    report = bending::analyse_bending_run(run);
  } catch (const std::exception&) {
    return;  // not a four-point bending run: the curve is all there is
  }
  const fs::path tmp = file.string() + ".tmp";
  {
    auto out = fmt::output_file(tmp.string());
    out.print("# crack_position={:.9g}\nsize\n",
              report.crack.found ? report.crack.position : std::numeric_limits<double>::quiet_NaN());
    for (double d : report.fragments.sizes) out.print("{:.9g}\n", d);
  }
  fs::rename(tmp, file);
}

void read_fracture(const fs::path& file, RunResult& r) {
  std::ifstream in(file);
  if (!in) return;  // a run cached before fracture outcomes were recorded
  std::string line;
  std::getline(in, line);
  const double crack = log_number(line, "crack_position=", std::numeric_limits<double>::quiet_NaN());
  if (std::isfinite(crack)) r.crack_position = crack;
  std::getline(in, line);  // header
  while (std::getline(in, line))
    if (!line.empty()) r.fragment_sizes.push_back(std::stod(line));
}

RunResult read_cached(const fs::path& file, const std::string& key) {
  RunResult r;
  r.curve = read_run_curve(file);
  read_fracture(fs::path(file).replace_extension(".fracture.csv"), r);
  r.key = key;
  r.cached = true;
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  r.kinetic_to_elastic = log_number(first, "kinetic_to_elastic=", 0);
  r.wall_seconds = log_number(first, "wall_seconds=", 0);
  return r;
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

std::vector<std::string> RunPool::full_overrides(const RunRequest& request) const {
  std::vector<std::string> o = request.overrides;
  o.push_back(fmt::format("simulation.seed={}", request.seed));
  return o;
}

std::vector<std::string> RunPool::seating_overrides(const RunRequest& request) const {
  const Scene scene = load_scene(request.scene, full_overrides(request), *host_);
  if (scene.stop.load_walls.empty()) return {};
  const Vec3 n = scene.stop.load_direction.normalized();
  const SceneInstance inst = instantiate(scene, *host_, [](const std::string&) {});
  const Particles& p = inst.simulation->particles();
  std::vector<std::string> out;
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
    const Vec3 seated = w.point + best * n;
    out.push_back(fmt::format("wall.{}.point=[{:.12g}, {:.12g}, {:.12g}]", w.name, seated.x(), seated.y(), seated.z()));
  }
  return out;
}

SpecimenSetup RunPool::specimen_setup(const fs::path& scene_file, const std::vector<std::string>& overrides,
                                      long seed) const {
  RunRequest request{scene_file, overrides, seed, false};
  const Scene scene = load_scene(scene_file, full_overrides(request), *host_);
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

double RunPool::scene_rate(const fs::path& scene_file, const std::vector<std::string>& overrides) const {
  const Scene scene = load_scene(scene_file, overrides, *host_);
  double rate = 0;
  for (const Wall& w : scene.walls)
    if (is_load_wall(scene, w))
      rate = std::max(rate, w.velocity.norm());
  return rate;
}

std::vector<std::string> RunPool::rate_overrides(const fs::path& scene_file, const std::vector<std::string>& overrides,
                                                 double rate) const {
  const Scene scene = load_scene(scene_file, overrides, *host_);
  const double own = scene_rate(scene_file, overrides);
  if (!(own > 0))
    throw std::runtime_error(fmt::format("{}: no moving [stop] load_walls, so the loading rate cannot be set to {} m/s",
                                         scene_file.string(), rate));
  if (std::abs(rate - own) <= 1e-9 * own) return {};
  const double f = rate / own;
  std::vector<std::string> out;
  for (const Wall& w : scene.walls)
    if (is_load_wall(scene, w)) {
      const Vec3 v = f * w.velocity;
      out.push_back(fmt::format("wall.{}.velocity=[{:.12g}, {:.12g}, {:.12g}]", w.name, v.x(), v.y(), v.z()));
      // The same ramp travel at the new speed: the ramp is f times shorter.
      if (w.motion.ramp != WallRamp::None)
        out.push_back(fmt::format("wall.{}.ramp_time={:.12g}", w.name, w.motion.ramp_time / f));
    }
  out.push_back(fmt::format("simulation.duration={:.12g}", scene.duration / f));
  if (scene.series_interval > 0) out.push_back(fmt::format("output.series_interval={:.12g}", scene.series_interval / f));
  return out;
}

std::vector<std::string> RunPool::ramp_overrides(const fs::path& scene_file, const std::vector<std::string>& overrides,
                                                 const std::string& ramp, double ramp_time) const {
  const Scene scene = load_scene(scene_file, overrides, *host_);
  std::vector<std::string> out;
  for (const Wall& w : scene.walls)
    if (is_load_wall(scene, w)) {
      out.push_back(fmt::format("wall.{}.ramp=\"{}\"", w.name, ramp));
      // With ramp = "none" a ramp_time of the scene's is ignored (the loader allows that pair).
      if (ramp != "none") out.push_back(fmt::format("wall.{}.ramp_time={:.12g}", w.name, ramp_time));
    }
  return out;
}

std::string RunPool::resolved_text(const RunRequest& request) const {
  std::vector<std::string> o = full_overrides(request);
  if (request.seat)
    for (auto& s : seating_overrides(request)) o.push_back(std::move(s));
  return load_scene(request.scene, o, *host_).resolved_text;
}

std::vector<RunResult> RunPool::run(const std::vector<RunRequest>& requests, std::ostream& log) {
  struct Job {
    std::string key;
    std::vector<std::string> args;
  };
  std::vector<RunResult> results(requests.size());
  std::vector<std::string> keys(requests.size());
  std::map<std::string, Job> pending;  // one job per distinct key
  const fs::path cache = work_dir_ / "cache";
  fs::create_directories(cache);
  const fs::path self = fs::read_symlink("/proc/self/exe");
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const RunRequest& r = requests[i];
    std::vector<std::string> o = full_overrides(r);
    if (r.seat)
      for (auto& s : seating_overrides(r)) o.push_back(std::move(s));
    keys[i] = fnv1a_hex(load_scene(r.scene, o, *host_).resolved_text);
    if (fs::exists(cache / (keys[i] + ".csv")) || pending.count(keys[i])) continue;
    Job job{keys[i], {self.string()}};
    for (const auto& d : plugin_dirs_) job.args.insert(job.args.end(), {"--plugin-dir", d.string()});
    job.args.insert(job.args.end(), {"run", r.scene.string(), "--threads", "1", "--checkpoint-every", "0"});
    for (const auto& s : o) job.args.insert(job.args.end(), {"--set", s});
    pending.emplace(keys[i], std::move(job));
  }

  std::vector<Job> queue;
  for (auto& [k, j] : pending) queue.push_back(std::move(j));
  std::vector<Child> running;
  std::size_t next = 0, done = 0;
  std::string failure;
  auto start = [&](std::size_t job) {
    Child c;
    c.job = job;
    c.dir = work_dir_ / "runs" / queue[job].key;
    fs::create_directories(c.dir);
    std::vector<std::string> args = queue[job].args;
    args.insert(args.end(), {"--out", c.dir.string()});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string log_file = (c.dir / "log.txt").string();
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    const int rc = posix_spawn(&c.pid, self.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error(fmt::format("cannot start {}: error {}", self.string(), rc));
    c.start = std::chrono::steady_clock::now();
    ++runs_started_;
    running.push_back(c);
  };
  auto finish = [&](const Child& c, int status) {
    const std::string child_log = read_text(c.dir / "log.txt");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      if (failure.empty())
        failure = fmt::format("a simulation failed (exit status {}); its log {}:\n{}", status,
                              (c.dir / "log.txt").string(), child_log.substr(child_log.size() > 3000 ? child_log.size() - 3000 : 0));
      return;
    }
    const measure::Curve curve = read_run_curve(c.dir / "run_curve.csv");
    const double ke = log_number(child_log, "kinetic/elastic energy before breakage <= ", 0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - c.start).count();
    const fs::path tmp = cache / (queue[c.job].key + ".tmp");
    {
      auto out = fmt::output_file(tmp.string());
      out.print("# kinetic_to_elastic={:.6g} wall_seconds={:.3f}\ntime,displacement,force\n", ke, seconds);
      for (std::size_t k = 0; k < curve.size(); ++k)
        out.print("{:.12g},{:.12g},{:.12g}\n", curve.time[k], curve.displacement[k], curve.force[k]);
    }
    write_fracture(c.dir / "run.h5", cache / (queue[c.job].key + ".fracture.csv"));
    fs::rename(tmp, cache / (queue[c.job].key + ".csv"));  // atomic: a killed diagnosis leaves no torn entry
    std::error_code ignored;
    fs::remove_all(c.dir, ignored);  // run.h5 and checkpoints: the curve is all the workflow uses
    ++done;
    fmt::print(log, "  run {}/{} done ({:.1f} s, kinetic/elastic {:.2g})\n", done, queue.size(), seconds, ke);
  };
  while (done < queue.size() && failure.empty()) {
    while (running.size() < static_cast<std::size_t>(workers_) && next < queue.size()) start(next++);
    bool reaped = false;
    for (std::size_t k = 0; k < running.size(); ++k) {
      int status = 0;
      if (waitpid(running[k].pid, &status, WNOHANG) == running[k].pid) {
        const Child c = running[k];
        running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
        finish(c, status);
        reaped = true;
        break;
      }
    }
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (const Child& c : running) {  // after a failure: wait for the others, keep what they finished
    int status = 0;
    waitpid(c.pid, &status, 0);
    finish(c, status);
  }
  if (!failure.empty()) throw std::runtime_error(failure);
  for (std::size_t i = 0; i < requests.size(); ++i) results[i] = read_cached(cache / (keys[i] + ".csv"), keys[i]);
  for (std::size_t i = 0; i < requests.size(); ++i)
    results[i].cached = !pending.count(keys[i]);
  return results;
}

}  // namespace shard
