#include "shard/driver/run_driver.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <algorithm>
#include <optional>
#include <span>
#include <sstream>

#include "run_loop_parts.hpp"
#include "run_restart.hpp"
#include "shard/bending/deformation_kinetic.hpp"
#include "shard/bending/quasi_static.hpp"
#include "shard/body_impacts.hpp"
#include "shard/checkpoint.hpp"
#include "shard/driver/numerical_health.hpp"
#include "shard/driver/output_folder.hpp"
#include "shard/driver/time_step_report.hpp"
#include "shard/output.hpp"
#include "shard/plugin_host.hpp"
#include "shard/run_file.hpp"
#include "shard/scene.hpp"
#include "shard/version.hpp"

namespace shard::driver {
// Shared with the decomposed run (mpi/distributed_run.cpp): run_loop_parts.hpp.
namespace detail {

// The run loop's own state that a checkpoint must carry besides the simulation's.
void save_loop_state(Checkpoint& c, const RunResult& r, int frames_written, const std::vector<double>& health) {
  c.numbers = {{"frames_written", frames_written},
               {"peak_load", r.peak_load},
               {"displacement_at_peak", r.displacement_at_peak},
               {"max_kinetic_to_elastic", r.max_kinetic_to_elastic}};
  c.arrays = {{"load", r.curve.load},
              {"displacement", r.curve.displacement},
              {"time_series", r.curve.time},
              {"kinetic_before_break", r.kinetic_before_break},
              {"elastic_before_break", r.elastic_before_break},
              {"health", health}};
}

void restore_loop_state(const Checkpoint& c, RunResult& r, int& frames_written) {
  frames_written = static_cast<int>(c.number("frames_written"));
  r.peak_load = c.number("peak_load");
  r.displacement_at_peak = c.number("displacement_at_peak");
  r.max_kinetic_to_elastic = c.number("max_kinetic_to_elastic");
  r.curve.load = c.array("load");
  r.curve.displacement = c.array("displacement");
  r.curve.time = c.array("time_series");
  r.kinetic_before_break = c.array("kinetic_before_break");
  r.elastic_before_break = c.array("elastic_before_break");
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

// What a restart may change: when the run ends. Every other key made the state in the checkpoint.
bool restart_may_change(const std::string& key) { return key == "simulation.duration" || key.rfind("stop.", 0) == 0; }

// The run file's scene with the restart's overrides. The frame and series schedule stays the
// run's own (by default it follows the duration), so the rows already written keep their places.
// A --set that repeats the run's own value (the first command line given again) changes nothing.
Scene restart_scene(const RunSpec& spec, const RunMetadata& meta, const PluginHost& host) {
  const Scene old = load_scene_text(meta.scene_text, meta.scene_file, host);
  for (const auto& o : spec.overrides)
    if (!restart_may_change(o.key) &&
        load_scene_text(meta.scene_text, meta.scene_file, host, SceneOverrides{o}).resolved_text != old.resolved_text)
      throw SceneError(fmt::format(
          "--restart {} with --set {}: a restart continues the state in the checkpoint, which the run's own {} made; "
          "only simulation.duration and [stop] keys may change on a restart (run the scene again for the others)",
          spec.restart.string(), o.text(), o.key));
  if (spec.overrides.empty()) return old;
  SceneOverrides o = spec.overrides;
  o.push_back({"output.frame_interval", old.frame_interval});
  o.push_back({"output.series_interval", old.series_interval});
  return load_scene_text(meta.scene_text, meta.scene_file, host, o);
}

RunStart read_run_start(const RunSpec& spec, const PluginHost& host, const RunLog& log,
                        const std::function<Checkpoint(const std::filesystem::path&)>& read) {
  RunStart start;
  start.restarting = !spec.restart.empty();
  if (start.restarting) {
    if (!std::filesystem::is_regular_file(spec.restart))
      throw OutputError(fmt::format("--restart {}: no such run file; give the run.h5 of the run to continue",
                                    spec.restart.string()));
    start.restart_point = read(checkpoint_path_for(spec.restart));
    start.old_meta = RunFile(spec.restart).metadata();
  }
  if (!start.restarting && std::filesystem::is_directory(spec.scene))
    throw SceneError(fmt::format("{}: is a folder, not a scene file; give the .toml file (scenes/ has examples)",
                                 spec.scene.string()));
  start.scene = start.restarting ? restart_scene(spec, start.old_meta, host) : load_scene(spec.scene, host, spec.overrides);
  // Breakage without a bond model is not an error (the default is on, and a contact-only scene
  // is legitimate), but asking for it explicitly means a [bond] section was forgotten.
  if (start.scene.breakage && !start.scene.bond && explicitly_sets_breakage(start.scene.resolved_text) &&
      log.warning)
    log.warning("breakage = true but the scene has no [bond] section: nothing can break. Add [bond] "
                "(plugin = \"beam_bond\") or remove breakage");
  return start;
}

std::string last_good_state(const RunResult& r) {
  return r.checkpoint_step < 0
             ? std::string("No checkpoint was written before it.")
             : fmt::format("The last good state is the checkpoint {} (step {}); after fixing the cause, start "
                           "again from the scene (a restart continues with the same settings)",
                           r.checkpoint.string(), r.checkpoint_step);
}

void prepare_run_output(const RunSpec& spec, const Scene& scene) {
  prepare_output_folder(spec.out_dir, "--out");
  const auto run_file = spec.out_dir / scene.output_file;
  if (std::filesystem::is_directory(run_file))
    throw OutputError(fmt::format("the run file '{}' is a folder; remove it or choose another folder with --out",
                                  run_file.string()));
}

RunMetadata run_metadata(const Scene& scene, const SceneInstance& inst, const PluginHost& host,
                         const RunLog& log) {
  const Simulation& sim = *inst.simulation;
  auto info = [&](const std::string& line) {
    if (log.info) log.info(line);
  };
  RunMetadata meta;
  const TimeStepReport time_step = time_step_report(scene, sim);
  for (const auto& [key, line] : time_step.limits) {
    info(line);
    meta.notes.emplace_back(key, line);
  }
  info(time_step.chosen);
  meta.notes.emplace_back("dt", fmt::format("{:.17g}", sim.dt()));
  for (const auto& [k, v] : inst.body.quality) info(fmt::format("packing {} = {:.6g}", k, v));
  meta.scene_text = scene.resolved_text;
  meta.scene_file = scene.file.string();
  meta.seed = scene.seed;
  // The code that ran it (shard/version.hpp); git_revision is empty for a build outside git.
  meta.shard_version = std::string(version());
  meta.git_revision = std::string(git_describe());
  meta.generator_quality = inst.body.quality;
  auto record = [&](PluginKind kind, const char* label, const PluginChoice& c, const std::string& body = {}) {
    const auto& p = host.find(kind, c.name);
    meta.plugins.emplace_back(fmt::format("{}/{}{}", label, c.name, body.empty() ? "" : "/" + body),
                              fmt::format("version={}; file={}; {}", p.info.version, p.file, describe(c.params)));
  };
  // One record per body entry: generator/<plugin>, or generator/<plugin>/<body name> for [[body]].
  for (const auto& b : scene.bodies)
    record(PluginKind::Generator, "generator", b.generator,
           b.from_generator_section ? "" : b.name);
  if (scene.contact) record(PluginKind::Contact, "contact", *scene.contact);
  if (scene.bond) record(PluginKind::Bond, "bond", *scene.bond);
  if (scene.bond)  // the out-of-tree bond effects composed onto the law (docs/how-to/write-a-plugin.md)
    for (const auto* e : host.bond_effects_on(scene.bond->name, scene.bond->params))
      meta.plugins.emplace_back("bond_effect/" + e->info.name,
                                fmt::format("version={}; file={}; on bond/{}", e->info.version, e->file, e->law));
  return meta;
}

// Up to the peak, as shard bending's report counts: after it a softening or brittle fall is the
// failure's own dynamics (reported as transients by compare), not the loading's. Softening bonds
// keep breakage away past the peak: the tiny beam at softening ratio 6.4 (seed 3) read 0.0051
// over all rows before the first break, 0.00028 up to the peak.
double kinetic_to_elastic_up_to_peak(const RunResult& r) {
  const auto& load = r.curve.load;
  const auto peak = static_cast<std::size_t>(std::max_element(load.begin(), load.end()) - load.begin());
  const std::size_t rows = std::min({peak + 1, r.kinetic_before_break.size(), r.elastic_before_break.size()});
  return bending::max_kinetic_to_elastic(std::span(load).first(std::min(rows, load.size())),
                                         std::span(r.kinetic_before_break).first(rows),
                                         std::span(r.elastic_before_break).first(rows), r.peak_load);
}

}  // namespace detail
using namespace detail;

RunResult run(const RunSpec& spec, const PluginHost& host, const std::vector<RunObserver*>& observers,
              const RunLog& log) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (spec.threads > 0) omp_set_num_threads(spec.threads);  // this thread's setting only
  // HDF5 1.10 closes its open files again at exit; a file whose flush failed (disk full) then
  // crashes that second close (measured: SIGSEGV in H5F__close_cb after the error was printed).
  // Shard closes every file through RAII, so the library's exit handler is not needed. It can only
  // be switched off before the library's first use and simply refuses afterwards.
  H5dont_atexit();
  auto info = [&](const std::string& line) {
    if (log.info) log.info(line);
  };
  RunStart start = read_run_start(spec, host, log, read_checkpoint);
  const bool restarting = start.restarting;
  const std::optional<Checkpoint>& restart_point = start.restart_point;
  const RunMetadata& old_meta = start.old_meta;
  const Scene& scene = start.scene;
  if (!restarting) prepare_run_output(spec, scene);
  SceneInstance inst = instantiate(scene, host, info);
  Simulation& sim = *inst.simulation;
  NumericalHealth health(sim);
  BodyImpactRecorder impacts(sim.particles());  // first wall contact per body (docs/reference/bodies.md)
  if (restart_point) {
    try {
      sim.import_state(restart_point->simulation);
    } catch (const std::invalid_argument& e) {
      throw CheckpointError(fmt::format("cannot continue from {}: {}", checkpoint_path_for(spec.restart).string(),
                                        e.what()));
    }
  }

  RunResult result;
  result.particles = sim.particles().size();
  // The network as the run began: a restart counts the bonds broken before it too, so the progress
  // line's intact / initial and broken add up.
  result.bonds_initial = sim.bonds().size() + static_cast<std::size_t>(sim.bonds_broken());
  result.dt = sim.dt();
  info(fmt::format("scene {}: {} particles, {} bonds, {} walls", scene.file.string(), result.particles,
                   result.bonds_initial, sim.walls().size()));
  RunMetadata meta = run_metadata(scene, inst, host, log);

  std::vector<std::string> wall_names;
  for (const auto& w : sim.walls()) wall_names.push_back(w.name);
  const auto series_every = std::max<std::int64_t>(1, std::llround(scene.series_interval / sim.dt()));
  const auto frame_every = std::max<std::int64_t>(1, std::llround(scene.frame_interval / sim.dt()));
  std::filesystem::path moved_aside;  // the interrupted run file, while its content is copied
  if (restarting) {
    result.output = spec.restart;
    meta = old_meta;
    moved_aside = spec.restart;
    moved_aside.replace_extension(".interrupted.h5");
    std::filesystem::rename(spec.restart, moved_aside);
  } else {
    result.output = spec.out_dir / scene.output_file;
  }
  const std::filesystem::path checkpoint_file = checkpoint_path_for(result.output);
  std::optional<RunWriter> writer_slot;
  try {
    writer_slot.emplace(result.output, meta, wall_names);
    if (restarting) {
      const auto copied = copy_run_prefix(moved_aside, *writer_slot, *restart_point, {series_every, frame_every},
                                           wall_names);
      writer_slot->flush();
      info(fmt::format("restart: continuing {} from step {} (t = {:.6g} s); {} frames and the series up to it kept",
                       result.output.string(), sim.step_count(), sim.time(), copied));
    }
  } catch (...) {
    // Put the interrupted run back as it was: a failed restart must not cost the user the run.
    if (restarting) {
      writer_slot.reset();
      std::error_code ignored;
      std::filesystem::rename(moved_aside, spec.restart, ignored);
    }
    throw;
  }
  if (restarting) std::filesystem::remove(moved_aside);
  RunWriter& writer = *writer_slot;

  const LoadSensor sensor(scene, sim);
  RunState state(scene, sim, result, sensor, [&] {
    Checkpoint c;
    c.simulation = sim.export_state();
    save_loop_state(c, result, state.frames_written, health.state());
    c.arrays.emplace_back("body_impacts", impacts.state());
    write_checkpoint(checkpoint_file, c);
    result.checkpoint = checkpoint_file;
    result.checkpoint_step = sim.step_count();
  });
  state.wall_start = wall_start;
  state.restarted = restarting;
  if (restart_point) {
    restore_loop_state(*restart_point, result, state.frames_written);
    health.restore(restart_point->array("health"));
    impacts.restore(restart_point->array("body_impacts"));
    result.restarted_from = sim.step_count();
  }
  auto last_good = [&] { return last_good_state(result); };
  auto write_frame = [&] {
    state.frame_labels = nullptr;
    for (auto* o : observers) o->before_frame(state);
    writer.write_frame(sim.step_count(), sim.time(), sim.particles(), sim.bonds(), state.frame_labels);
    ++state.frames_written;
  };
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
    for (const auto& w : sim.walls()) row.add_wall(w);
    writer.append_series(row);
    writer.append_break_events(sim.take_new_break_events());
    if (!std::isfinite(e.kinetic)) health.check(sim, last_good());
    // Less the rigid-body motion: a beam sliding on its rollers strains nothing.
    record_curve_point(result, sim.time(), sensor.load(sim), sensor.displacement(sim), sim.bonds_broken() == 0,
                       e.bond + e.contact, [&] { return bending::deformation_kinetic_energy(sim.particles()); });
    return e;
  };

  LoopHooks loop{[&] { return sim.step_count(); },
                 [&] {
                   sim.step();
                   health.after_step(sim);
                   impacts.update(sim);
                 },
                 [&] { health.check(sim, last_good()); },
                 series_row,
                 write_frame,
                 [](std::int64_t) {}};
  run_observed_steps(state, observers, scene.duration, sim.dt(), restarting,
                     {series_every, frame_every, spec.health_every}, loop);
  writer.write_body_impacts(impacts.impacts());
  writer.flush();

  result.steps = sim.step_count();
  result.time = sim.time();
  result.bonds_broken = sim.bonds_broken();
  result.final_displacement = sensor.displacement(sim);
  if (!sensor.empty())
    result.max_kinetic_to_elastic = kinetic_to_elastic_up_to_peak(result);
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  for (auto* o : observers) o->on_finish(state);
  return result;
}

}  // namespace shard::driver
