#pragma once
// Reads the particles and bonds of one frame of a Shard run file (run.h5, layout in
// docs/reference/output-format.md) through shard::h5, the run-file layer under shard::RunFile as well: the
// same opening checks, format version and rule for complete frames.
#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

#include "shard/types.hpp"

namespace shard::from_file {

struct RunFrame {
  std::size_t index = 0;  // k of /frames/<k:06d>
  std::size_t frame_count = 0;
  std::int64_t step = 0;
  double time = 0;                 // s
  std::vector<Vec3> position;      // m
  std::vector<double> radius;      // m
  std::vector<std::int32_t> material;
  std::vector<std::pair<Index, Index>> bonds;  // row indices into this frame's arrays
};

// frame >= 0: that frame; frame < 0: counted from the end (-1 = the last complete frame).
// Throws std::runtime_error naming the file and the defect (not HDF5, not a run file, a newer
// format version, no such frame, inconsistent dataset shapes).
RunFrame read_run_frame(const std::filesystem::path& path, long frame);

}  // namespace shard::from_file
