#pragma once
#include <filesystem>
#include <string>

#include "shard/plugin_host.hpp"

namespace shard::test {

// The measurement loop's tiny beam (~160 spheres): a run to a millimetre's pin travel takes a
// second or two on one core.
inline const std::filesystem::path kTinyBeam = std::filesystem::path(SHARD_SOURCE_DIR) / "scenes/measurements/tiny_bending.toml";

// Loaded once per test binary; shared read-only by the runs, as the measurement loop shares its host.
inline const PluginHost& plugins() {
  static PluginHost host;
  static const bool loaded = [] {
    host.load_directories(PluginHost::default_search_path());
    return true;
  }();
  (void)loaded;
  return host;
}

inline std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "shard_driver_tests" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace shard::test
