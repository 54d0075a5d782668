#pragma once
// A command's output folder is made (or found usable) before the command's work starts, so a
// folder that cannot exist -- `--out` below an existing file, say -- fails at once instead of
// after the simulation it was meant to hold.
#include <filesystem>
#include <string>

namespace shard {

// Creates `folder` and its parents; throws OutputError naming the folder, the reason and
// `option` (e.g. "--out") as the way to choose another one.
void prepare_output_folder(const std::filesystem::path& folder, const std::string& option);

}  // namespace shard
