#pragma once
// Writing a whole file so that a reader sees the old content or the new, never a part: the text goes
// to a temporary file beside the target ("<name>.tmp.<pid>", the same file system, so the rename is
// atomic), is flushed to disk (fsync) and is renamed over the target.
#include <filesystem>
#include <string_view>

namespace shard::io {

// Throws std::runtime_error naming `file` and the system's reason when any step fails; the
// temporary file is removed then.
void write_file_atomically(const std::filesystem::path& file, std::string_view content);

}  // namespace shard::io
