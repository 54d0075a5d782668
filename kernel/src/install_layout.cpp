#include "shard/install_layout.hpp"

#include <dlfcn.h>

#include <system_error>

// Defined by cmake/ShardLayout.cmake for this file alone: SHARD_BUILD_IMAGE_DIR (where the binary
// holding this code is built), SHARD_BUILD_PLUGIN_DIR, SHARD_SOURCE_DIR, and the install layout
// relative to the prefix: SHARD_LIBDIR_TO_PREFIX, SHARD_PLUGIN_SUBDIR, SHARD_DATA_SUBDIR.

namespace shard {
namespace {

// The file this code was loaded from: libshard_kernel.so, or the program it is compiled into.
std::filesystem::path own_image() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&install_layout), &info) == 0 || info.dli_fname == nullptr) return {};
  std::error_code ec;
  const auto file = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? std::filesystem::path(info.dli_fname) : file;
}

}  // namespace

InstallLayout install_layout() {
  const std::filesystem::path image_dir = own_image().parent_path();
  std::error_code ec;
  if (!image_dir.empty() && std::filesystem::equivalent(image_dir, SHARD_BUILD_IMAGE_DIR, ec))
    return {SHARD_BUILD_PLUGIN_DIR, SHARD_SOURCE_DIR, true};
  const std::filesystem::path prefix = (image_dir / SHARD_LIBDIR_TO_PREFIX).lexically_normal();
  return {prefix / SHARD_PLUGIN_SUBDIR, prefix / SHARD_DATA_SUBDIR, false};
}

}  // namespace shard
