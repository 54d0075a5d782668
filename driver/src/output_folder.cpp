#include "shard/driver/output_folder.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "shard/output.hpp"

namespace shard {

void prepare_output_folder(const std::filesystem::path& folder, const std::string& option) {
  if (folder.empty()) return;  // the current folder
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  std::string reason = error ? error.message() : std::string();
  if (!error && !std::filesystem::is_directory(folder, error)) reason = "it is a file, not a folder";
  if (reason.empty() && ::access(folder.c_str(), W_OK | X_OK) != 0) reason = std::strerror(errno);
  if (!reason.empty())
    throw OutputError(fmt::format("cannot create the output folder '{}': {}. Choose a folder you can write to with {}",
                                  folder.string(), reason, option));
}

}  // namespace shard
