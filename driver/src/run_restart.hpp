#pragma once
// The output side of `shard run --restart run.h5`: the interrupted run file is moved aside and a
// new one is written holding exactly what the uninterrupted run had written up to the
// checkpoint (the frames and series rows on their schedule, the break events handed to the
// output), so the restarted run then appends the same rows and frames an uninterrupted run would.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "shard/checkpoint.hpp"
#include "shard/output.hpp"

namespace shard {

struct RestartCadence {
  std::int64_t series_every = 1;  // steps between series rows
  std::int64_t frame_every = 1;   // steps between frames
};

// Copies from `old_file` into `writer` every frame and series row with step <= the checkpoint's
// that lies on the cadence, and the checkpoint's already-written break events. Returns the
// number of frames copied.
// `walls` are the writer's wall names in its order (the scene's).
std::int64_t copy_run_prefix(const std::filesystem::path& old_file, RunWriter& writer, const Checkpoint& checkpoint,
                             const RestartCadence& cadence, const std::vector<std::string>& walls);

}  // namespace shard
