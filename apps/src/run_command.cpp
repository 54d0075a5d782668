#include "shard/app/run_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <omp.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <iostream>
#include <ostream>

#include "shard/analysis/components.hpp"
#include "shard/output.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

namespace shard {
namespace {

// Set by SIGINT; a signal handler can only touch a lock-free flag, so this one flag is global.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) { g_interrupted = 1; }

class InterruptGuard {
 public:
  InterruptGuard() { previous_ = std::signal(SIGINT, on_interrupt); }
  ~InterruptGuard() { std::signal(SIGINT, previous_); }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  void (*previous_)(int);
};

std::string seconds_text(double s) {
  if (!std::isfinite(s)) return "--";
  if (s < 120) return fmt::format("{:.0f}s", s);
  if (s < 7200) return fmt::format("{:.0f}m{:02.0f}s", std::floor(s / 60), std::fmod(s, 60));
  return fmt::format("{:.1f}h", s / 3600);
}

struct LoadSensor {
  std::vector<std::size_t> walls;
  Vec3 direction;
  // The particles push back against the motion of the loading walls.
  double load(const Simulation& sim) const {
    double f = 0;
    for (auto w : walls) f -= sim.walls()[w].force.dot(direction);
    return f;
  }
  double displacement(const Simulation& sim) const {
    if (walls.empty()) return 0;
    double d = 0;
    for (auto w : walls) d += sim.walls()[w].displacement.dot(direction);
    return d / static_cast<double>(walls.size());
  }
};

}  // namespace

void load_plugins(PluginHost& host, const std::vector<std::filesystem::path>& dirs, std::ostream& log) {
  for (const auto& refused : host.load_directories(PluginHost::default_search_path(dirs)))
    fmt::print(log, "warning: {}\n", refused);
}

RunSummary run_scene(const RunOptions& options, std::ostream& log_stream) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (options.threads > 0) omp_set_num_threads(options.threads);
  auto log = [&](const std::string& line) {
    if (!options.quiet) fmt::print(log_stream, "{}\n", line);
  };
  PluginHost host;
  load_plugins(host, options.plugin_dirs, log_stream);
  const Scene scene = load_scene(options.scene, options.overrides, host);
  SceneInstance inst = instantiate(scene, host, log);
  Simulation& sim = *inst.simulation;

  RunSummary summary;
  summary.particles = sim.particles().size();
  summary.bonds_initial = sim.bonds().size();
  summary.dt = sim.dt();
  log(fmt::format("scene {}: {} particles, {} bonds, {} walls", scene.file.string(), summary.particles,
                  summary.bonds_initial, sim.walls().size()));
  RunMetadata meta;
  for (const auto& l : sim.time_step_limits()) {
    const std::string line = fmt::format("time step limit {}: critical {:.4g} s, recommended {:.4g} s", l.name,
                                         l.critical, l.recommended);
    log(line);
    meta.notes.emplace_back("dt_" + l.name, line);
  }
  log(fmt::format("time step dt = {:.4g} s ({}), {} steps for {:.4g} s", sim.dt(), scene.dt > 0 ? "set" : "auto",
                  static_cast<std::int64_t>(std::ceil(scene.duration / sim.dt())), scene.duration));
  meta.notes.emplace_back("dt", fmt::format("{:.17g}", sim.dt()));
  for (const auto& [k, v] : inst.body.quality) log(fmt::format("packing {} = {:.6g}", k, v));

  meta.scene_text = scene.resolved_text;
  meta.scene_file = scene.file.string();
  meta.seed = scene.seed;
  meta.shard_version = SHARD_VERSION;
  meta.git_revision = SHARD_GIT_REVISION;
  meta.generator_quality = inst.body.quality;
  auto record = [&](const char* kind, const PluginChoice& c) {
    const auto& p = host.find(kind[0] == 'g' ? PluginKind::Generator : kind[0] == 'c' ? PluginKind::Contact
                                                                                      : PluginKind::Bond,
                              c.name);
    meta.plugins.emplace_back(fmt::format("{}/{}", kind, c.name),
                              fmt::format("version={}; file={}; {}", p.info.version, p.file, describe(c.params)));
  };
  record("generator", scene.generator);
  if (scene.contact) record("contact", *scene.contact);
  if (scene.bond) record("bond", *scene.bond);

  std::filesystem::create_directories(options.out_dir);
  summary.output = options.out_dir / scene.output_file;
  std::vector<std::string> wall_names;
  for (const auto& w : sim.walls()) wall_names.push_back(w.name);
  RunWriter writer(summary.output, meta, wall_names);

  LoadSensor sensor;
  sensor.direction = scene.stop.load_direction;
  for (const auto& name : scene.stop.load_walls)
    for (std::size_t w = 0; w < sim.walls().size(); ++w)
      if (sim.walls()[w].name == name) sensor.walls.push_back(w);

  analysis::UnionFindLabeller labeller;
  std::vector<Index> labels;
  int frames_written = 0;
  auto write_frame = [&] {
    const bool label = scene.fragments_every > 0 && frames_written % scene.fragments_every == 0;
    if (label) {
      const auto& b = sim.bonds();
      const auto count = labeller.label(sim.particles().size(), {b.i, b.j}, labels);
      analysis::canonicalise_labels(labels, count, sim.particles().mass, sim.particles().id);
    }
    writer.write_frame(sim.step_count(), sim.time(), sim.particles(), sim.bonds(), label ? &labels : nullptr);
    ++frames_written;
  };

  const auto series_every = std::max<std::int64_t>(1, std::llround(scene.series_interval / sim.dt()));
  const auto frame_every = std::max<std::int64_t>(1, std::llround(scene.frame_interval / sim.dt()));
  const auto total_steps = static_cast<std::int64_t>(std::ceil(scene.duration / sim.dt() - 1e-9));
  InterruptGuard interrupt_guard;
  g_interrupted = 0;

  auto series_row = [&] {
    SeriesRow row;
    row.step = sim.step_count();
    row.time = sim.time();
    const Energies e = sim.energies();
    row.kinetic_energy = e.kinetic;
    row.bond_energy = e.bond;
    row.contact_energy = e.contact;
    row.bonds_intact = static_cast<std::int64_t>(sim.bonds().size());
    row.bonds_broken = sim.bonds_broken();
    row.contacts = static_cast<std::int64_t>(sim.contact_count());
    for (const auto& w : sim.walls()) {
      row.wall_force.push_back(w.force);
      row.wall_torque.push_back(w.torque);
      row.wall_displacement.push_back(w.displacement);
    }
    writer.append_series(row);
    writer.append_break_events(sim.take_new_break_events());
    if (!std::isfinite(e.kinetic))
      throw std::runtime_error(fmt::format(
          "step {} (t = {:.6g} s): the kinetic energy is not finite: the run blew up. Likely causes: a time step "
          "above the stiffest bond's limit (dt = {:.4g} s) or overlapping initial particles",
          sim.step_count(), sim.time(), sim.dt()));
    const double load = sensor.load(sim);
    const double disp = sensor.displacement(sim);
    summary.load.push_back(load);
    summary.displacement.push_back(disp);
    summary.time_series.push_back(sim.time());
    if (load > summary.peak_load) {
      summary.peak_load = load;
      summary.displacement_at_peak = disp;
    }
    if (sim.bonds_broken() == 0 && load > 0.2 * summary.peak_load && summary.peak_load > 0) {
      const double elastic = e.bond + e.contact;
      if (elastic > 0) summary.max_kinetic_to_elastic = std::max(summary.max_kinetic_to_elastic, e.kinetic / elastic);
    }
    return e;
  };

  write_frame();
  series_row();
  auto last_progress = std::chrono::steady_clock::now();
  const std::int64_t start_step = sim.step_count();
  while (sim.step_count() < total_steps) {
    sim.step();
    const std::int64_t s = sim.step_count();
    if (s % series_every == 0) {
      const Energies e = series_row();
      if (scene.stop.after_peak_fraction > 0 && sim.bonds_broken() > 0 &&
          sensor.load(sim) < scene.stop.after_peak_fraction * summary.peak_load) {
        summary.stop_reason = fmt::format("load fell below {:.0f} % of its peak after breakage",
                                          100 * scene.stop.after_peak_fraction);
        break;
      }
      if (scene.stop.max_displacement > 0 && sensor.displacement(sim) >= scene.stop.max_displacement) {
        summary.stop_reason = "the loading walls reached max_displacement";
        break;
      }
      const auto now = std::chrono::steady_clock::now();
      // On a terminal the line rewrites itself every second; in a log file it appears every 10 s.
      const bool tty = &log_stream == &std::cerr && isatty(STDERR_FILENO);
      if (!options.quiet && now - last_progress > std::chrono::seconds(tty ? 1 : 10)) {
        last_progress = now;
        const double elapsed = std::chrono::duration<double>(now - wall_start).count();
        const double rate = static_cast<double>(s - start_step) / std::max(1e-9, elapsed);
        fmt::print(log_stream,
                   "step {:>9} t={:.4e}s KE={:.3e}J load={:.4g}N bonds {}/{} broken {} {:.0f} steps/s ETA {}{}",
                   s, sim.time(), e.kinetic, sensor.load(sim), sim.bonds().size(), summary.bonds_initial,
                   sim.bonds_broken(), rate, seconds_text(static_cast<double>(total_steps - s) / rate), tty ? "\r" : "\n");
        log_stream.flush();
      }
    }
    if (s % frame_every == 0) write_frame();
    if (g_interrupted) {
      summary.stop_reason = "interrupted (SIGINT): state written, file complete";
      break;
    }
  }
  if (summary.stop_reason.empty()) summary.stop_reason = "reached the scene's duration";
  if (sim.step_count() % series_every != 0) series_row();
  if (sim.step_count() % frame_every != 0) write_frame();
  writer.flush();

  summary.steps = sim.step_count();
  summary.time = sim.time();
  summary.bonds_broken = sim.bonds_broken();
  summary.final_displacement = sensor.displacement(sim);
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (!options.quiet) fmt::print(log_stream, "\n");
  log(fmt::format("done: {} ({}); {} steps, t = {:.4g} s, {} bonds broken, {:.1f} s wall", summary.output.string(),
                  summary.stop_reason, summary.steps, summary.time, summary.bonds_broken, summary.wall_seconds));
  if (!sensor.walls.empty()) {
    log(fmt::format("peak load {:.5g} N at displacement {:.5g} m; kinetic/elastic energy before breakage <= {:.3g}",
                    summary.peak_load, summary.displacement_at_peak, summary.max_kinetic_to_elastic));
    const auto csv = summary.output.parent_path() / (summary.output.stem().string() + "_curve.csv");
    std::ofstream out(csv);
    out << "time_s,displacement_m,force_N\n";
    for (std::size_t k = 0; k < summary.load.size(); ++k)
      out << fmt::format("{:.9g},{:.9g},{:.9g}\n", summary.time_series[k], summary.displacement[k], summary.load[k]);
    log(fmt::format("load curve: {}", csv.string()));
  }
  return summary;
}

}  // namespace shard
