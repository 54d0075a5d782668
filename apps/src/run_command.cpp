#include "shard/app/run_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <hdf5.h>
#include <omp.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <span>
#include <sstream>
#include <iostream>
#include <optional>
#include <ostream>

#include "numerical_health.hpp"
#include "output_folder.hpp"
#include "run_restart.hpp"
#include "shard/analysis/components.hpp"
#include "shard/bending/deformation_kinetic.hpp"
#include "shard/bending/quasi_static.hpp"
#include "shard/checkpoint.hpp"
#include "shard/output.hpp"
#include "shard/run_file.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

namespace shard {
namespace {

// Set by SIGINT; a signal handler can only touch a lock-free flag, so this one flag is global.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) { g_interrupted = 1; }

class SignalGuard {
 public:
  SignalGuard(int signal, void (*handler)(int)) : signal_(signal), previous_(std::signal(signal, handler)) {}
  ~SignalGuard() { std::signal(signal_, previous_); }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  int signal_;
  void (*previous_)(int);
};

// The run loop's own state that a checkpoint must carry besides the simulation's.
void save_loop_state(Checkpoint& c, const RunSummary& summary, int frames_written, const NumericalHealth& health) {
  c.numbers = {{"frames_written", frames_written},
               {"peak_load", summary.peak_load},
               {"displacement_at_peak", summary.displacement_at_peak},
               {"max_kinetic_to_elastic", summary.max_kinetic_to_elastic}};
  c.arrays = {{"load", summary.load},
              {"displacement", summary.displacement},
              {"time_series", summary.time_series},
              {"kinetic_before_break", summary.kinetic_before_break},
              {"elastic_before_break", summary.elastic_before_break},
              {"health", health.state()}};
}

void restore_loop_state(const Checkpoint& c, RunSummary& summary, int& frames_written, NumericalHealth& health) {
  frames_written = static_cast<int>(c.number("frames_written"));
  summary.peak_load = c.number("peak_load");
  summary.displacement_at_peak = c.number("displacement_at_peak");
  summary.max_kinetic_to_elastic = c.number("max_kinetic_to_elastic");
  summary.load = c.array("load");
  summary.displacement = c.array("displacement");
  summary.time_series = c.array("time_series");
  summary.kinetic_before_break = c.array("kinetic_before_break");
  summary.elastic_before_break = c.array("elastic_before_break");
  health.restore(c.array("health"));
}

double max_kinetic_to_elastic(const RunSummary& summary) {
  // Up to the peak, as shard bending's report counts: after it a softening or brittle fall is the
  // failure's own dynamics (reported as transients by compare), not the loading's. Softening bonds
  // keep breakage away past the peak: the tiny beam at softening ratio 6.4 (seed 3) read 0.0051
  // over all rows before the first break, 0.00028 up to the peak.
  const auto peak = static_cast<std::size_t>(std::max_element(summary.load.begin(), summary.load.end()) -
                                             summary.load.begin());
  const std::size_t rows = std::min({peak + 1, summary.kinetic_before_break.size(), summary.elastic_before_break.size()});
  return bending::max_kinetic_to_elastic(std::span(summary.load).first(std::min(rows, summary.load.size())),
                                         std::span(summary.kinetic_before_break).first(rows),
                                         std::span(summary.elastic_before_break).first(rows), summary.peak_load);
}

// True when a line of the scene reads `breakage = true` (blanks allowed around the words).
// Plain scanning: GCC 12 warns falsely inside std::regex in the sanitizer build.
bool explicitly_sets_breakage(const std::string& scene_text) {
  std::istringstream lines(scene_text);
  for (std::string line; std::getline(lines, line);) {
    std::string compact;
    for (char ch : line)
      if (ch != ' ' && ch != '\t') compact += ch;
    if (compact.rfind("breakage=true", 0) == 0) return true;
  }
  return false;
}

// Writes the curve CSV and says so if the disk refused it.
void write_curve_csv(const std::filesystem::path& csv, const RunSummary& summary) {
  std::ofstream out(csv);
  out << "time_s,displacement_m,force_N\n";
  for (std::size_t k = 0; k < summary.load.size(); ++k)
    out << fmt::format("{:.9g},{:.9g},{:.9g}\n", summary.time_series[k], summary.displacement[k], summary.load[k]);
  out.close();
  if (!out)
    throw OutputError(fmt::format("cannot write the load curve '{}' (disk full or folder not writable); the run "
                                  "file {} is complete",
                                  csv.string(), summary.output.string()));
}

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
  // A full disk or a file-size limit must surface as a write error, not kill the process.
  const SignalGuard file_size_guard(SIGXFSZ, SIG_IGN);
  // HDF5 1.10 closes its open files again at exit; a file whose flush failed (disk full) then
  // crashes that second close (measured: SIGSEGV in H5F__close_cb after the error was printed).
  // Shard closes every file through RAII, so the library's exit handler is not needed. It can only
  // be switched off before the library's first use and simply refuses afterwards.
  H5dont_atexit();
  auto log = [&](const std::string& line) {
    if (!options.quiet) fmt::print(log_stream, "{}\n", line);
  };
  PluginHost host;
  load_plugins(host, options.plugin_dirs, log_stream);
  const bool restarting = !options.restart.empty();
  std::optional<Checkpoint> restart_point;
  RunMetadata old_meta;
  if (restarting) {
    // Both are read before anything is built, so a missing checkpoint fails at once.
    if (!std::filesystem::is_regular_file(options.restart))
      throw OutputError(fmt::format("--restart {}: no such run file; give the run.h5 of the run to continue",
                                    options.restart.string()));
    restart_point = read_checkpoint(checkpoint_path_for(options.restart));
    old_meta = RunFile(options.restart).metadata();
  }
  if (!restarting && std::filesystem::is_directory(options.scene))
    throw SceneError(fmt::format("{}: is a folder, not a scene file; give the .toml file (scenes/ has examples)",
                                 options.scene.string()));
  const Scene scene = restarting ? load_scene_text(old_meta.scene_text, old_meta.scene_file, {}, host)
                                 : load_scene(options.scene, options.overrides, host);
  // Breakage without a bond model is not an error (the default is on, and a contact-only scene
  // is legitimate), but asking for it explicitly means a [bond] section was forgotten.
  if (scene.breakage && !scene.bond && explicitly_sets_breakage(scene.resolved_text))
    fmt::print(log_stream,
               "warning: breakage = true but the scene has no [bond] section: nothing can break. Add [bond] "
               "(plugin = \"beam_bond\") or remove breakage\n");
  // The output folder before the generator: an unusable --out must not cost the packing's time.
  if (!restarting) {
    prepare_output_folder(options.out_dir, "--out");
    const auto run_file = options.out_dir / scene.output_file;
    if (std::filesystem::is_directory(run_file))
      throw OutputError(fmt::format("the run file '{}' is a folder; remove it or choose another folder with --out",
                                    run_file.string()));
  }
  SceneInstance inst = instantiate(scene, host, log);
  Simulation& sim = *inst.simulation;
  NumericalHealth health(sim);
  if (restart_point) {
    try {
      sim.import_state(restart_point->simulation);
    } catch (const std::invalid_argument& e) {
      throw CheckpointError(fmt::format("cannot continue from {}: {}", checkpoint_path_for(options.restart).string(),
                                        e.what()));
    }
  }

  RunSummary summary;
  summary.particles = sim.particles().size();
  // The network as the run began: a restart counts the bonds broken before it too, so the progress
  // line's intact / initial and broken add up.
  summary.bonds_initial = sim.bonds().size() + static_cast<std::size_t>(sim.bonds_broken());
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

  std::vector<std::string> wall_names;
  for (const auto& w : sim.walls()) wall_names.push_back(w.name);
  const auto series_every = std::max<std::int64_t>(1, std::llround(scene.series_interval / sim.dt()));
  const auto frame_every = std::max<std::int64_t>(1, std::llround(scene.frame_interval / sim.dt()));
  std::filesystem::path moved_aside;  // the interrupted run file, while its content is copied
  if (restarting) {
    summary.output = options.restart;
    meta = old_meta;
    moved_aside = options.restart;
    moved_aside.replace_extension(".interrupted.h5");
    std::filesystem::rename(options.restart, moved_aside);
  } else {
    summary.output = options.out_dir / scene.output_file;
  }
  const std::filesystem::path checkpoint_file = checkpoint_path_for(summary.output);
  std::optional<RunWriter> writer_slot;
  try {
    writer_slot.emplace(summary.output, meta, wall_names);
    if (restarting) {
      const auto copied = copy_run_prefix(moved_aside, *writer_slot, *restart_point, {series_every, frame_every});
      writer_slot->flush();
      log(fmt::format("restart: continuing {} from step {} (t = {:.6g} s); {} frames and the series up to it kept",
                      summary.output.string(), sim.step_count(), sim.time(), copied));
    }
  } catch (...) {
    // Put the interrupted run back as it was: a failed restart must not cost the user the run.
    if (restarting) {
      writer_slot.reset();
      std::error_code ignored;
      std::filesystem::rename(moved_aside, options.restart, ignored);
    }
    throw;
  }
  if (restarting) std::filesystem::remove(moved_aside);
  RunWriter& writer = *writer_slot;

  LoadSensor sensor;
  sensor.direction = scene.stop.load_direction;
  for (const auto& name : scene.stop.load_walls)
    for (std::size_t w = 0; w < sim.walls().size(); ++w)
      if (sim.walls()[w].name == name) sensor.walls.push_back(w);

  analysis::UnionFindLabeller labeller;
  std::vector<Index> labels;
  int frames_written = 0;
  if (restart_point) {
    restore_loop_state(*restart_point, summary, frames_written, health);
    summary.restarted_from = sim.step_count();
  }
  auto checkpoint = [&] {
    Checkpoint c;
    c.simulation = sim.export_state();
    save_loop_state(c, summary, frames_written, health);
    write_checkpoint(checkpoint_file, c);
    summary.checkpoint = checkpoint_file;
    summary.checkpoint_step = sim.step_count();
  };
  auto last_good = [&] {
    return summary.checkpoint_step < 0
               ? std::string("No checkpoint was written before it.")
               : fmt::format("The last good state is the checkpoint {} (step {}); after fixing the cause, start "
                             "again from the scene (a restart continues with the same settings)",
                             summary.checkpoint.string(), summary.checkpoint_step);
  };
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

  const auto total_steps = static_cast<std::int64_t>(std::ceil(scene.duration / sim.dt() - 1e-9));
  const SignalGuard interrupt_guard(SIGINT, on_interrupt);
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
    if (!std::isfinite(e.kinetic)) health.check(sim, last_good());
    const double load = sensor.load(sim);
    const double disp = sensor.displacement(sim);
    summary.load.push_back(load);
    summary.displacement.push_back(disp);
    summary.time_series.push_back(sim.time());
    if (load > summary.peak_load) {
      summary.peak_load = load;
      summary.displacement_at_peak = disp;
    }
    if (sim.bonds_broken() == 0) {
      // Less the rigid-body motion: a beam sliding on its rollers strains nothing.
      summary.kinetic_before_break.push_back(bending::deformation_kinetic_energy(sim.particles()));
      summary.elastic_before_break.push_back(e.bond + e.contact);
    }
    return e;
  };

  if (!restarting) {
    health.check(sim, last_good());
    write_frame();
    series_row();
    checkpoint();
  }
  auto last_progress = std::chrono::steady_clock::now();
  const std::int64_t start_step = sim.step_count();
  const std::int64_t health_every = std::max(1, options.health_every);
  while (sim.step_count() < total_steps) {
    sim.step();
    health.after_step(sim);
    const std::int64_t s = sim.step_count();
    if (s % health_every == 0 || s % frame_every == 0) health.check(sim, last_good());
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
    if (s % frame_every == 0) {
      write_frame();
      if (options.checkpoint_every > 0 && (frames_written - 1) % options.checkpoint_every == 0) checkpoint();
    }
    if (s == options.interrupt_at_step) g_interrupted = 1;
    if (g_interrupted) {
      // The checkpoint first: the closing row and frame below take break events from the
      // simulation, and the checkpoint must hold the state the loop would have continued with.
      if (summary.checkpoint_step != s) checkpoint();
      summary.interrupted = true;
      summary.stop_reason = fmt::format("interrupted (SIGINT) at step {}: checkpoint written; continue with shard "
                                        "run --restart {}",
                                        s, summary.output.string());
      break;
    }
  }
  if (summary.stop_reason.empty()) summary.stop_reason = "reached the scene's duration";
  if (sim.step_count() % series_every != 0) series_row();
  if (sim.step_count() % frame_every != 0) write_frame();
  if (!summary.interrupted && summary.checkpoint_step != sim.step_count()) checkpoint();
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
    summary.max_kinetic_to_elastic = max_kinetic_to_elastic(summary);
    log(fmt::format("peak load {:.5g} N at displacement {:.5g} m; kinetic/elastic energy before breakage <= {:.3g}",
                    summary.peak_load, summary.displacement_at_peak, summary.max_kinetic_to_elastic));
    const auto csv = summary.output.parent_path() / (summary.output.stem().string() + "_curve.csv");
    write_curve_csv(csv, summary);
    log(fmt::format("load curve: {}", csv.string()));
  }
  return summary;
}

}  // namespace shard
