#pragma once
// The rules that end a run before its duration. The scene's [stop] rules read the load sensor at
// every series row; the interrupt rule ends the run at a step (Ctrl-C, or a test's chosen step).
#include <cstdint>

#include "shard/driver/run_observer.hpp"

namespace shard::driver {

// [stop] after_peak_fraction: the load fell below that fraction of its peak after a bond broke.
class LoadDropStop : public RunObserver {
 public:
  void on_series(RunState& run, const Energies& energies) override;
};

// [stop] max_displacement: the loading walls travelled that far.
class MaxDisplacementStop : public RunObserver {
 public:
  void on_series(RunState& run, const Energies& energies) override;
};

// [stop] rest_speed, rest_time: the run is at rest once the largest particle speed, taken after
// every step, stayed below rest_speed at every step spanning rest_time (the first such step ends
// it). The clock starts at the loop's first step (or its start, when every particle is slower
// then); a restart starts it anew, so a restarted run may end up to rest_time later. Cost: one
// pass over the velocities per step, left at the first particle that is too fast; decomposed over
// MPI ranks, each rank passes over its own and one MPI_Allreduce of an integer per step combines them.
class RestStop : public RunObserver {
 public:
  void on_start(RunState& run) override;
  void on_step(RunState& run) override;

 private:
  void look(RunState& run);
  double still_since_ = -1;  // s: the time since which every particle is slower; < 0: one is not
};

// SIGINT (Ctrl-C) or SIGTERM (what mpirun sends every rank when it is interrupted, and what a
// batch scheduler sends at a job's time limit), caught while this object lives (the previous
// handlers come back after), or reaching `at_step` (>= 0), stops the run after the current step
// with StopReason::Interrupted. A CheckpointWriter composed with it writes the state to continue
// from. One may live at a time: a signal reaches the process, not a run.
class InterruptStop : public RunObserver {
 public:
  explicit InterruptStop(std::int64_t at_step = -1);
  ~InterruptStop() override;
  InterruptStop(const InterruptStop&) = delete;
  InterruptStop& operator=(const InterruptStop&) = delete;
  void on_step(RunState& run) override;

 private:
  std::int64_t at_step_;
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

}  // namespace shard::driver
