// scenes/belt_roller.toml end to end through `shard run`'s code: the scene's belt and roller keys
// reach the kernel and every wall's wear indicator reaches the run file. (The analytic facts of
// turning walls, belts and the impact energy are tested on single bodies, tests/kernel.)
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shard/app/run_command.hpp"
#include "shard/run_file.hpp"

using namespace shard;

namespace {

double mean_x(const FrameData& frame) {
  double sum = 0;
  for (const auto& x : frame.position) sum += x.x();
  return sum / static_cast<double>(frame.position.size());
}

}  // namespace

TEST_CASE("scenes/belt_roller: the belt carries the pile into the roller, and the run file records the walls' wear") {
  RunOptions options;
  options.scene = std::filesystem::path(SHARD_SOURCE_DIR) / "scenes/belt_roller.toml";
  options.out_dir = std::filesystem::temp_directory_path() / "shard_test_belt_roller";
  options.quiet = true;
  std::ostringstream log;
  const RunSummary summary = run_scene(options, log);
  RunFile run(summary.output);
  REQUIRE(run.wall_names() == std::vector<std::string>{"belt", "guide_left", "guide_right", "roller"});
  const std::size_t rows = run.series_rows();
  REQUIRE(rows > 10);
  for (const std::string& wall : run.wall_names()) {
    CAPTURE(wall);
    const auto impacts = run.read_wall_impacts(wall);
    const auto energy = run.read_wall_impact_energy(wall);
    REQUIRE(impacts.size() == rows);
    REQUIRE(energy.size() == rows);
    // Counts since the start: an impact is never taken back.
    CHECK(std::is_sorted(impacts.begin(), impacts.end()));
    CHECK(impacts.back() > 0);
    // Dissipated energy: positive once the pile has landed and slid (the contacts' elastic
    // energy, subtracted, is far smaller than a single landing's loss).
    CHECK(energy.back() > 0);
  }
  // The roller stands 7 cm downstream, past the pile's front at 3 cm: only the belt can have
  // carried spheres to it, and it was struck.
  const auto roller = run.read_wall_impacts("roller");
  CHECK(roller.front() == 0);
  CHECK(roller.back() > 0);
  // Along x only the belt drives the pile (the guides' normals are along y, the roller pushes
  // back): its centre moved downstream, by less than the belt's 7.5 cm (0.3 m/s x 0.25 s).
  const double moved = mean_x(run.read_frame(run.frame_count() - 1)) - mean_x(run.read_frame(0));
  CHECK(moved > 0.0);
  CHECK(moved < 0.3 * 0.25);
}

TEST_CASE("scenes/belt_roller's materials: the rubber belt (mu 0.9) gets the pile moving sooner than a steel one (mu 0.3)") {
  // The same scene with the belt made of steel (docs/reference/materials.md): only the cake-belt pair's
  // friction and restitution change. The pile starts at rest on the running belt; friction drags
  // its bottom layer up to the belt's 0.3 m/s within v / (mu g) = 34 ms on rubber, 102 ms on
  // steel, so early on the rubber belt has carried the pile further. (Later the roller holds both
  // piles back alike.)
  const auto dir = std::filesystem::temp_directory_path() / "shard_test_belt_roller_materials";
  std::filesystem::create_directories(dir);
  std::ifstream in(std::filesystem::path(SHARD_SOURCE_DIR) / "scenes/belt_roller.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string steel = text.str();
  const std::string rubber_belt = "shape = \"plane\"\nmaterial = \"rubber\"";
  REQUIRE(steel.find(rubber_belt) != std::string::npos);
  steel.replace(steel.find(rubber_belt), rubber_belt.size(), "shape = \"plane\"\nmaterial = \"steel\"");
  std::ofstream(dir / "steel_belt.toml") << steel;
  const std::filesystem::path scenes[2] = {std::filesystem::path(SHARD_SOURCE_DIR) / "scenes/belt_roller.toml",
                                           dir / "steel_belt.toml"};
  std::vector<double> moved[2];
  for (int k = 0; k < 2; ++k) {
    RunOptions options;
    options.scene = scenes[k];
    options.out_dir = dir / (k == 0 ? "rubber" : "steel");
    options.quiet = true;
    options.overrides = parse_overrides({"simulation.duration=0.06", "output.frame_interval=0.01"});
    std::ostringstream log;
    const RunSummary summary = run_scene(options, log);
    RunFile run(summary.output);
    for (std::size_t f = 0; f < run.frame_count(); ++f)
      moved[k].push_back(mean_x(run.read_frame(f)) - mean_x(run.read_frame(0)));
  }
  REQUIRE(moved[0].size() == moved[1].size());
  for (std::size_t f = 1; f < moved[0].size(); ++f) {
    CAPTURE(f);
    MESSAGE("frame " << f << ": pile's mean advance on rubber " << moved[0][f] * 1e3 << " mm, on steel "
                     << moved[1][f] * 1e3 << " mm");
    CHECK(moved[0][f] > moved[1][f]);
  }
}
