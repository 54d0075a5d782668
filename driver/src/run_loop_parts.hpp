#pragma once
// The pieces of a scene's run (run_scene.cpp): the observed step loop itself, a point of the load
// curve, what a checkpoint carries of the loop, the run file's metadata, and the closing figures.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shard/checkpoint.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/run_observer.hpp"
#include "shard/output.hpp"
#include "shard/scene.hpp"
#include "whole_scene.hpp"

namespace shard::driver::detail {

// The loop's counters and curve; `health` is the energy watch's state (NumericalHealth::state),
// restored by the caller from the array "health".
void save_loop_state(Checkpoint& c, const RunResult& r, int frames_written, const std::vector<double>& health);
void restore_loop_state(const Checkpoint& c, RunResult& r, int& frames_written);
bool explicitly_sets_breakage(const std::string& scene_text);

// What a run starts from: the scene file with its overrides, or on --restart the interrupted
// run's own scene and its checkpoint, read by `read` (the decomposed run also checks the ids);
// both files are read before anything is built, so a bad one fails at once. Warns when a scene
// asks for breakage without a bond model.
struct RunStart {
  bool restarting = false;
  std::optional<Checkpoint> restart_point;
  RunMetadata old_meta;
  Scene scene;
};
RunStart read_run_start(const RunSpec& spec, const PluginHost& host, const RunLog& log,
                        const std::function<Checkpoint(const std::filesystem::path&)>& read);
// The output folder of a new run, before the generator: an unusable --out must not cost the
// packing's time.
void prepare_run_output(const RunSpec& spec, const Scene& scene);
// The run file's metadata of a new run, and the lines the run's log shows of it (time step,
// packing quality), from the whole scene's figures.
struct RunMetadataDraft {
  RunMetadata meta;
  std::vector<std::string> lines;
};
RunMetadataDraft run_metadata(const Scene& scene, const WholeScene& whole, const PluginHost& host);
double kinetic_to_elastic_up_to_peak(const RunResult& r);
// Where a numerical error's message sends the user: the last checkpoint, if any.
std::string last_good_state(const RunResult& r);

// A point of the load-displacement curve and the running peak; while no bond has broken, the
// deformation kinetic energy (`kinetic()`, less the rigid-body motion) beside the elastic one for
// the quasi-static check.
template <class DeformationKinetic>
void record_curve_point(RunResult& r, double time, double load, double displacement, bool intact, double elastic,
                        DeformationKinetic&& kinetic) {
  r.curve.force.push_back(load);
  r.curve.displacement.push_back(displacement);
  r.curve.time.push_back(time);
  if (load > r.peak_load) {
    r.peak_load = load;
    r.displacement_at_peak = displacement;
  }
  if (intact) {
    r.kinetic_before_break.push_back(kinetic());
    r.elastic_before_break.push_back(elastic);
  }
}

// How often, in steps, the loop writes a series row and a frame and checks the numerical health.
struct LoopCadence {
  std::int64_t series_every = 1;
  std::int64_t frame_every = 1;
  std::int64_t health_every = 1;
};

// What a driver does at the loop's points: the step count, one time step with what follows it,
// the health check, a series row (returning its energies), a frame, and after the observers of a
// step (the decomposed run agrees there on a stop asked on one rank).
template <class StepCount, class Step, class CheckHealth, class SeriesRow, class WriteFrame, class AfterStep>
struct LoopHooks {
  StepCount step_count;
  Step step;
  CheckHealth check_health;
  SeriesRow series_row;
  WriteFrame write_frame;
  AfterStep after_step;
};

// The observed step loop: a new run's first health check, frame and series row (a restart has
// them), the observers' hooks in order until one asks to stop, the closing row and frame.
template <class Hooks>
void run_observed_steps(RunState& state, const std::vector<RunObserver*>& observers, double duration, double dt,
                        bool restarting, const LoopCadence& every, Hooks& loop) {
  state.total_steps = static_cast<std::int64_t>(std::ceil(duration / dt - 1e-9));
  if (!restarting) {
    loop.check_health();
    loop.write_frame();
    loop.series_row();
  }
  state.start_step = loop.step_count();
  for (auto* o : observers) o->on_start(state);
  const std::int64_t health_every = std::max<std::int64_t>(1, every.health_every);
  // Calls `hook` on every observer in order until one asks the run to stop.
  auto notify = [&](auto&& hook) {
    for (auto* o : observers) {
      hook(*o);
      if (state.stop_requested()) return;
    }
  };
  while (loop.step_count() < state.total_steps && !state.stop_requested()) {
    loop.step();
    const std::int64_t s = loop.step_count();
    if (s % health_every == 0 || s % every.frame_every == 0) loop.check_health();
    if (s % every.series_every == 0) {
      const Energies e = loop.series_row();
      notify([&](RunObserver& o) { o.on_series(state, e); });
      if (state.stop_requested()) break;
    }
    if (s % every.frame_every == 0) {
      loop.write_frame();
      notify([&](RunObserver& o) { o.on_frame(state); });
      if (state.stop_requested()) break;
    }
    notify([&](RunObserver& o) { o.on_step(state); });
    loop.after_step(s);
  }
  if (!state.stop_requested()) state.request_stop(StopReason::Duration, "reached the scene's duration");
  for (auto* o : observers) o->on_stop(state);
  if (loop.step_count() % every.series_every != 0) loop.series_row();
  if (loop.step_count() % every.frame_every != 0) loop.write_frame();
  for (auto* o : observers) o->on_closed(state);
}

}  // namespace shard::driver::detail
