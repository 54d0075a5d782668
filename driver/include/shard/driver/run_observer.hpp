#pragma once
// The hooks of the run loop. The driver owns the simulation, the run file and the numerical-
// health watch; everything a caller may or may not want -- stop rules, checkpoints, fragment
// labels, the progress line, the closing report -- is an observer, called in the order the
// caller composed them. A hook runs on the run's own thread; none is called per particle pair.
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "shard/driver/load_sensor.hpp"
#include "shard/driver/run_result.hpp"
#include "shard/scene.hpp"
#include "shard/simulation.hpp"

namespace shard::driver {

// What observers see of a run and may do to it.
class RunState {
 public:
  RunState(const Scene& scene_, Simulation& sim_, RunResult& result_, const LoadSensor& sensor_,
           std::function<void()> checkpoint)
      : scene(scene_), sim(sim_), result(result_), sensor(sensor_), checkpoint_(std::move(checkpoint)) {}

  const Scene& scene;
  Simulation& sim;
  RunResult& result;  // filled as the run goes: the curve so far, the checkpoint, the stop
  const LoadSensor& sensor;
  std::int64_t total_steps = 0;
  std::int64_t start_step = 0;  // where this loop began (a restart's checkpoint step)
  std::chrono::steady_clock::time_point wall_start;
  int frames_written = 0;
  bool restarted = false;
  // Set by a before_frame hook: the per-particle fragment labels the next frame stores.
  const std::vector<Index>* frame_labels = nullptr;

  // A run decomposed over MPI ranks (driver/distributed_run.hpp) sets this: `sim` is then one
  // rank's share (its step, time, dt and walls are the run's), and these are the whole run's.
  struct Whole {
    std::int64_t bonds_broken = 0;
    std::size_t bonds_intact = 0;
    // In before_frame of a frame to be labelled: labels the fragments of the next frame where its
    // particles are (collective: every rank calls it at the same hook). Fills `labels` with this
    // rank's rows of the frame and `sizes` with the particles per fragment, largest first, on
    // rank 0 (empty elsewhere).
    std::function<void(std::vector<Index>& labels, std::vector<std::size_t>& sizes)> label_fragments;
    // Whether every particle of the run is slower than the speed given (m/s), decided over all
    // ranks: collective, so every rank asks at the same hook (RestStop's on_start and on_step).
    std::function<bool(double)> all_slower_than;
  };
  const Whole* whole = nullptr;
  std::int64_t bonds_broken() const { return whole ? whole->bonds_broken : sim.bonds_broken(); }
  std::size_t bonds_intact() const { return whole ? whole->bonds_intact : sim.bonds().size(); }

  // Ends the loop after the current hook round; the first request wins.
  void request_stop(StopReason reason, std::string words) {
    if (stop_requested_) return;
    stop_requested_ = true;
    result.stop = reason;
    result.stop_reason = std::move(words);
  }
  bool stop_requested() const { return stop_requested_; }
  // Writes a checkpoint of the simulation and the loop (result.checkpoint, checkpoint_step).
  void write_checkpoint() { checkpoint_(); }

 private:
  std::function<void()> checkpoint_;
  bool stop_requested_ = false;
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // Before the first step of the loop (a fresh run's first frame, series row are written).
  virtual void on_start(RunState&) {}
  // After a series row of the loop was recorded (result.curve has it); `energies` are its own.
  virtual void on_series(RunState&, const Energies& /*energies*/) {}
  // Before any frame is written (the first, the loop's, the closing one).
  virtual void before_frame(RunState&) {}
  // After a frame of the loop was written.
  virtual void on_frame(RunState&) {}
  // At the end of every step of the loop, after its series row and frame.
  virtual void on_step(RunState&) {}
  // The loop ended (result.stop says why), before the closing series row and frame.
  virtual void on_stop(RunState&) {}
  // The closing series row and frame are written; the run file is not yet flushed.
  virtual void on_closed(RunState&) {}
  // The run file is complete and the result filled.
  virtual void on_finish(RunState&) {}
};

}  // namespace shard::driver
