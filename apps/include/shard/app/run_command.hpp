#pragma once
// `shard run`: a scene from file to run.h5, with a progress line and a stop rule.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace shard {

class Simulation;

struct RunOptions {
  std::filesystem::path scene;
  std::vector<std::string> overrides;  // --set section.key=value
  std::filesystem::path out_dir = ".";
  std::vector<std::filesystem::path> plugin_dirs;
  int threads = 0;  // 0: OpenMP default
  bool quiet = false;
};

struct RunSummary {
  std::filesystem::path output;
  std::int64_t steps = 0;
  double time = 0;
  double dt = 0;
  std::size_t particles = 0;
  std::size_t bonds_initial = 0;
  std::int64_t bonds_broken = 0;
  double peak_load = 0;                 // N, on the load walls along the loading direction
  double displacement_at_peak = 0;      // m
  double final_displacement = 0;        // m
  double wall_seconds = 0;
  std::string stop_reason;
  std::vector<double> load, displacement, time_series;  // the load curve, one row per series row
  double max_kinetic_to_elastic = 0;    // quasi-static check over the loading part
};

// Runs the scene; progress and log lines go to `log` (nothing when quiet).
RunSummary run_scene(const RunOptions& options, std::ostream& log);

// Loads plugins from --plugin-dir, $SHARD_PLUGIN_PATH, the build and the install tree.
class PluginHost;
void load_plugins(PluginHost& host, const std::vector<std::filesystem::path>& dirs, std::ostream& log);

}  // namespace shard
