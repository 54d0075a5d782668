#pragma once
// The run file's layout (docs/reference/output-format.md) as both of its readers see it: shard::RunFile in
// the kernel and the from_file generator plugin, which may not link the kernel. Opening a file,
// its format version, and whether a frame was written completely are decided here once.
//
// Format version: run.h5 carries an integer root attribute `format_version`, written by the run
// writer. A file without it was written before the attribute existed and is read as version 1; a
// file of a newer version than kRunFormatVersion is refused (its layout may mean something this
// reader does not know). Raise kRunFormatVersion when a dataset or attribute changes meaning or
// disappears; adding one does not need it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "h5_handle.hpp"

namespace shard::h5 {

inline constexpr std::int64_t kRunFormatVersion = 1;

enum class RunAccess { read, read_write };

// Opens `path` as a run file. Throws OutputError naming the path and the fix when it is missing, a
// folder, no HDF5 file, cannot be opened (for writing: read-only or still running), has no /frames
// group (a checkpoint?) or is of a newer format version than this reader.
Handle open_run_file(const std::filesystem::path& path, RunAccess access);

// The file's `format_version` attribute; 1 when it has none.
std::int64_t run_format_version(hid_t file);
void write_run_format_version(hid_t file);

// "frames/000012": the path of frame k below the root.
std::string frame_path(std::size_t k);
// What a frame group lacks of the layout, "" when it is complete: a kill may have torn the last
// frame, and the writer sets the step and time attributes after the datasets.
std::string frame_missing_part(hid_t group);
// As frame_missing_part(group).empty(), false when the group cannot even be read.
bool frame_complete(hid_t group);

}  // namespace shard::h5
