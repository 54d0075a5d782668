#include "shard/driver/checkpoint_writer.hpp"

namespace shard::driver {

void CheckpointWriter::on_start(RunState& run) {
  if (!run.restarted) run.write_checkpoint();
}

void CheckpointWriter::on_frame(RunState& run) {
  if (every_ > 0 && (run.frames_written - 1) % every_ == 0) run.write_checkpoint();
}

// The interrupt's checkpoint comes before the closing row and frame: those take break events
// from the simulation, and the checkpoint must hold the state the loop would have continued with.
void CheckpointWriter::on_stop(RunState& run) {
  if (run.result.interrupted() && run.result.checkpoint_step != run.sim.step_count()) run.write_checkpoint();
}

void CheckpointWriter::on_closed(RunState& run) {
  if (!run.result.interrupted() && run.result.checkpoint_step != run.sim.step_count()) run.write_checkpoint();
}

}  // namespace shard::driver
