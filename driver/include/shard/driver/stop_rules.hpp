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

// SIGINT, caught while this object lives (the previous handler comes back after), or reaching
// `at_step` (>= 0), stops the run with StopReason::Interrupted. A CheckpointWriter composed with it
// writes the state to continue from. One may live at a time: a signal reaches the process, not a run.
class InterruptStop : public RunObserver {
 public:
  explicit InterruptStop(std::int64_t at_step = -1);
  ~InterruptStop() override;
  InterruptStop(const InterruptStop&) = delete;
  InterruptStop& operator=(const InterruptStop&) = delete;
  void on_step(RunState& run) override;

 private:
  std::int64_t at_step_;
  void (*previous_)(int);
};

}  // namespace shard::driver
