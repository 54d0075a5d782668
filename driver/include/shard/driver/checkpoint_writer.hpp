#pragma once
// Checkpoints (run.checkpoint.h5 beside the run file) to continue a run from: after the first
// frame, every `every`-th frame (0: none in between), where an interrupt stops the run and at its
// end. Without this observer a run writes none (the measurement loop's runs need none).
#include "shard/driver/run_observer.hpp"

namespace shard::driver {

class CheckpointWriter : public RunObserver {
 public:
  explicit CheckpointWriter(int every) : every_(every) {}
  void on_start(RunState& run) override;
  void on_frame(RunState& run) override;
  void on_stop(RunState& run) override;
  void on_closed(RunState& run) override;

 private:
  int every_;
};

}  // namespace shard::driver
