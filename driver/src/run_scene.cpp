#include "run_scene.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "health_watch.hpp"
#include "impact_tracker.hpp"
#include "run_loop_parts.hpp"
#include "run_restart.hpp"
#include "shard/driver/load_sensor.hpp"
#include "shard/plugin_host.hpp"
#include "shard/run_file.hpp"

namespace shard::driver::detail {
namespace {

using Info = std::function<void(const std::string&)>;

// The backend's simulation from the instantiated scene or the restart's checkpoint; a state it
// cannot hold is the checkpoint's fault on a restart, the scene's otherwise.
void start_backend(RunBackend& backend, const RunSpec& spec, const RunStart& start, ScenePart& part) {
  try {
    backend.start(start.scene, part, start.restart_point ? &start.restart_point->simulation : nullptr);
  } catch (const std::invalid_argument& e) {
    if (start.restarting)
      throw CheckpointError(fmt::format("cannot continue from {}: {}", checkpoint_path_for(spec.restart).string(),
                                        e.what()));
    throw SceneError(fmt::format("{}: {}", start.scene.file.string(), e.what()));
  }
}

// The automatic step is the bonds' critical one, which Cundall's damping shortens
// (damped_stable_step). The settling, whose damping is heavy, takes the shortened step when the
// step is automatic; its state is the loading's start, not part of the curve, so the loading keeps
// the automatic step. A step the scene gives is kept throughout.
bool settling_shortens_step(const Scene& scene) { return !(scene.dt > 0); }

double settling_step(const Scene& scene, double dt) {
  return settling_shortens_step(scene) ? damped_stable_step(dt, scene.settle_damping) : dt;
}

// The Cundall damping that can bring the stable step below the run's, and its key: the settling's
// only when its step is not shortened for it.
RunDamping limiting_damping(const Scene& scene) {
  if (!settling_shortens_step(scene) && scene.settle_time > 0 && scene.settle_damping > scene.global_damping)
    return {scene.settle_damping, "settle_damping"};
  return {scene.global_damping, "global_damping"};
}

// A lab seats its pins on the settled specimen before the test starts, so they do not meet it at
// the test's speed: each [stop] load wall (a cylinder) is brought along load_direction until it
// touches the body.
void seat_load_walls(RunBackend& backend, const Scene& scene, const RunLog& log) {
  const Vec3 n = scene.stop.load_direction.normalized();
  for (std::size_t w = 0; w < backend.local().walls().size(); ++w) {
    const Wall& wall = backend.local().walls()[w];
    if (!scene.stop.is_load_wall(wall.name)) continue;
    const Particles& p = backend.local().particles();
    double first = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double s = backend.owns(k) ? cylinder_touch_offset(wall, n, p.position[k], p.radius[k], true)
                                      : std::numeric_limits<double>::quiet_NaN();
      if (!std::isnan(s)) first = std::min(first, s);
    }
    const std::vector<double> each = backend.gather_over_ranks({first});
    first = *std::min_element(each.begin(), each.end());
    if (!std::isfinite(first) || first <= 0) continue;  // nothing under it, or on the body already
    backend.on_all([&] { backend.local().shift_wall(w, first * n); });
    if (log.info) log.info(fmt::format("seated {} {:.4g} mm along the load direction onto the settled body", wall.name, first * 1e3));
  }
}

// The body at rest under gravity before the loading ([simulation] settle_time): the walls held,
// the settling damping, the clock from -settle_time to 0. Says how far from rest it came, as the
// kinetic energy left against the work its weight did while it settled.
void settle(RunBackend& backend, const Scene& scene, const RunLog& log) {
  const double dt = settling_step(scene, backend.local().dt());
  const auto steps = static_cast<std::int64_t>(std::ceil(scene.settle_time / dt));
  const Energies before = backend.energies();
  backend.on_all([&] { backend.local().begin_settling(static_cast<double>(steps) * dt, scene.settle_damping, dt); });
  for (std::int64_t k = 0; k < steps; ++k) backend.step();
  backend.on_all([&] { backend.local().end_settling(); });
  const Energies after = backend.energies();
  const double weight_work = before.gravity - after.gravity;
  const double left = weight_work > 0 ? after.kinetic / weight_work : 0.0;
  if (log.info)
    log.info(fmt::format("settled {:g} s ({} steps of {:.4g} s, damping {:g}): kinetic energy {:.3g} J left, {:.2g} "
                         "of the {:.3g} J its weight did",
                         scene.settle_time, steps, dt, scene.settle_damping, after.kinetic, left, weight_work));
  if (left > 0.01 && log.warning)
    log.warning(fmt::format("{}: the body is still moving after settling ({:.2g} of its weight's work is kinetic "
                            "energy); raise [simulation] settle_time or settle_damping",
                            scene.file.string(), left));
  seat_load_walls(backend, scene, log);
}

// Opens `writer` on the run file: a new one, or on a restart a new one holding the interrupted run's content up to
// the checkpoint. A failed restart puts the interrupted run back as it was: it must not cost the
// user the run.
void open_run_file(std::optional<RunWriter>& writer, const RunSpec& spec, const RunStart& start,
                   const RunMetadata& meta, const std::vector<std::string>& walls, const LoopCadence& every,
                   const std::filesystem::path& output, const RunBackend& backend, const Info& info) {
  if (!start.restarting) {
    backend.on_all([&] { writer.emplace(output, meta, walls, backend.run_file_access()); });
    return;
  }
  std::filesystem::path moved_aside = spec.restart;
  moved_aside.replace_extension(".interrupted.h5");
  backend.on_root([&] { std::filesystem::rename(spec.restart, moved_aside); });
  try {
    backend.on_all([&] {  // every rank reads the interrupted file and writes its prefix alike
      writer.emplace(output, meta, walls, backend.run_file_access());
      const auto copied =
          copy_run_prefix(moved_aside, *writer, *start.restart_point, {every.series_every, every.frame_every}, walls);
      writer->flush();
      const Simulation& sim = backend.local();
      info(fmt::format("restart: continuing {} from step {} (t = {:.6g} s){}; {} frames and the series up to it kept",
                       output.string(), sim.step_count(), sim.time(), backend.where(), copied));
    });
  } catch (...) {
    writer.reset();
    backend.barrier();
    if (backend.rank() == 0) {
      std::error_code ignored;
      std::filesystem::rename(moved_aside, spec.restart, ignored);
    }
    throw;
  }
  backend.on_root([&] { std::filesystem::remove(moved_aside); });
}

// The loop's work at each of its points (run_loop_parts.hpp's LoopHooks), over the backend.
class SceneLoop {
 public:
  SceneLoop(RunBackend& backend, RunWriter& writer, RunState& state, NumericalHealth& health, ImpactTracker& impacts,
            const std::vector<RunObserver*>& observers)
      : backend_(backend), writer_(writer), state_(state), health_(health), impacts_(impacts), observers_(observers) {}

  void step() {
    backend_.step();
    health_.after_step(backend_);
    impacts_.update(backend_);
  }
  void check_health() { health_.check(backend_, last_good_state(state_.result)); }
  void write_frame() {
    backend_.write_frame(writer_, state_, [&] {
      for (auto* o : observers_) o->before_frame(state_);
    });
    ++state_.frames_written;
  }
  Energies series_row();
  // The stop rules read the run's walls and counts, the same on every rank: they stop alike. A
  // signal reaches the ranks one by one (SIGINT sent to one, mpirun's SIGTERM to all at slightly
  // different steps): a stop asked on one stops all here.
  void agree_on_stop(std::int64_t step) {
    if (backend_.any_rank(state_.stop_requested()) && !state_.stop_requested())
      state_.request_stop(StopReason::Interrupted,
                          fmt::format("interrupted (a signal reached another rank) at step {}: checkpoint written; "
                                      "continue with shard run --restart {}",
                                      step, state_.result.output.string()));
  }

 private:
  RunBackend& backend_;
  RunWriter& writer_;
  RunState& state_;
  NumericalHealth& health_;
  ImpactTracker& impacts_;
  const std::vector<RunObserver*>& observers_;
};

Energies SceneLoop::series_row() {
  const Simulation& sim = backend_.local();
  SeriesRow row;
  row.step = sim.step_count();
  row.time = sim.time();
  const Energies e = backend_.energies();
  row.kinetic_energy = e.kinetic;
  row.bond_energy = e.bond;
  row.contact_energy = e.contact;
  row.bonds_intact = static_cast<std::int64_t>(backend_.bond_count());
  row.bonds_broken = backend_.bonds_broken();
  row.contacts = static_cast<std::int64_t>(backend_.contact_count());
  // A wall's dissipated work and impacts are counted by each rank for its own contacts.
  std::vector<double> own;
  for (const Wall& w : sim.walls()) own.insert(own.end(), {w.contact_work, static_cast<double>(w.impacts)});
  const std::vector<double> total = backend_.sum_over_ranks(own);
  for (std::size_t w = 0; w < sim.walls().size(); ++w) {
    Wall summed = sim.walls()[w];
    summed.contact_work = total[2 * w];
    summed.impacts = static_cast<std::int64_t>(total[2 * w + 1]);
    row.add_wall(summed);
  }
  const std::vector<BondBreakEvent> events = backend_.take_new_break_events();
  backend_.on_all([&] {
    writer_.append_series(row);
    writer_.append_break_events(events);
  });
  if (!std::isfinite(e.kinetic)) check_health();
  // Less the rigid-body motion: a beam sliding on its rollers strains nothing.
  const analysis::PinReading pins = state_.sensor.read(sim);
  record_curve_point(state_.result, sim.time(), pins.force(), pins.displacement(), backend_.bonds_broken() == 0,
                     e.bond + e.contact, [&] { return backend_.deformation_kinetic_energy(); });
  return e;
}

// A checkpoint of the simulation and of the loop.
void save_checkpoint(const RunBackend& backend, RunState& state, const NumericalHealth& health,
                      const ImpactTracker& impacts, const std::filesystem::path& file) {
  Checkpoint c;
  save_loop_state(c, state.result, state.frames_written, health.state(backend));
  c.arrays.emplace_back("body_impacts", impacts.state());
  backend.write_checkpoint(c, file);
  state.result.checkpoint = file;
  state.result.checkpoint_step = backend.local().step_count();
}

// The closing figures of the result.
void finish_result(RunResult& r, const RunBackend& backend, const LoadSensor& sensor,
                   std::chrono::steady_clock::time_point wall_start) {
  const Simulation& sim = backend.local();
  r.steps = sim.step_count();
  r.time = sim.time();
  r.bonds_broken = backend.bonds_broken();
  r.final_displacement = sensor.displacement(sim);
  if (!sensor.empty()) r.max_kinetic_to_elastic = kinetic_to_elastic_up_to_peak(r);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
}

}  // namespace

RunResult run_scene(const RunSpec& spec, const PluginHost& host, const std::vector<RunObserver*>& observers,
                    const RunLog& log_all, RunBackend& backend) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (spec.threads > 0) omp_set_num_threads(spec.threads);  // this thread's setting only
  // HDF5 1.10 closes its open files again at exit; a file whose flush failed (disk full) then
  // crashes that second close (measured: SIGSEGV in H5F__close_cb after the error was printed).
  // Shard closes every file through RAII, so the library's exit handler is not needed. It can only
  // be switched off before the library's first use and simply refuses afterwards.
  H5dont_atexit();
  const RunLog log = backend.rank() == 0 ? log_all : RunLog{};  // rank 0 speaks for the run
  const Info info = [&](const std::string& line) {
    if (log.info) log.info(line);
  };
  // Every rank reads the restart's files (read-only), so a bad one is refused alike everywhere.
  const RunStart start =
      read_run_start(spec, host, log, [&](const std::filesystem::path& c) { return backend.read_restart(c); });
  const Scene& scene = start.scene;
  if (!start.restarting) backend.on_root([&] { prepare_run_output(spec, scene); });
  // The scene generated once (the whole of it in one process, the models alone in the others);
  // the health watch, the impacts and the metadata read the whole scene's figures.
  ScenePart part = backend.instantiate(scene, host, info);
  NumericalHealth health(part.whole, part.instance.simulation.get(), scene.gravity, limiting_damping(scene));
  ImpactTracker impacts(part.whole.bodies);  // first wall contact per body (docs/reference/bodies.md)
  const RunMetadataDraft draft = run_metadata(scene, part.whole, host);
  RunResult result;
  result.particles = start.restart_point ? start.restart_point->simulation.particles.size() : part.whole.particles;
  start_backend(backend, spec, start, part);
  if (!start.restarting && scene.settle_time > 0) settle(backend, scene, log);
  Simulation& sim = backend.local();
  // The network as the run began: a restart counts the bonds broken before it too, so the progress
  // line's intact / initial and broken add up.
  result.bonds_initial = backend.bond_count() + static_cast<std::size_t>(backend.bonds_broken());
  result.dt = sim.dt();
  info(fmt::format("scene {}: {} particles, {} bonds, {} walls{}", scene.file.string(), result.particles,
                   result.bonds_initial, sim.walls().size(), backend.where()));
  for (const auto& line : draft.lines) info(line);
  RunMetadata meta = start.restarting ? start.old_meta : draft.meta;
  backend.add_notes(meta, start.restarting);

  std::vector<std::string> wall_names;
  for (const auto& w : sim.walls()) wall_names.push_back(w.name);
  const LoopCadence every{std::max<std::int64_t>(1, std::llround(scene.series_interval / sim.dt())),
                          std::max<std::int64_t>(1, std::llround(scene.frame_interval / sim.dt())), spec.health_every};
  result.output = start.restarting ? spec.restart : spec.out_dir / scene.output_file;
  std::optional<RunWriter> writer;  // not movable: opened in place
  open_run_file(writer, spec, start, meta, wall_names, every, result.output, backend, info);

  const LoadSensor sensor(scene, sim);
  const std::filesystem::path checkpoint_file = checkpoint_path_for(result.output);
  RunState state(scene, sim, result, sensor,
                 [&] { save_checkpoint(backend, state, health, impacts, checkpoint_file); });
  state.whole = backend.whole();
  state.wall_start = wall_start;
  state.restarted = start.restarting;
  if (start.restart_point) {
    restore_loop_state(*start.restart_point, result, state.frames_written);
    health.restore(start.restart_point->array("health"), backend.rank());
    impacts.restore(start.restart_point->array("body_impacts"));
    result.restarted_from = sim.step_count();
  }
  SceneLoop loop(backend, *writer, state, health, impacts, observers);
  LoopHooks hooks{[&] { return backend.local().step_count(); }, [&] { loop.step(); }, [&] { loop.check_health(); },
                  [&] { return loop.series_row(); }, [&] { loop.write_frame(); },
                  [&](std::int64_t s) { loop.agree_on_stop(s); }};
  run_observed_steps(state, observers, scene.duration, sim.dt(), start.restarting, every, hooks);
  backend.on_all([&] {
    writer->write_body_impacts(impacts.impacts());
    writer->flush();
  });
  finish_result(result, backend, sensor, wall_start);
  for (auto* o : observers) o->on_finish(state);
  return result;
}

}  // namespace shard::driver::detail
