#pragma once
// A scene that blows up from its initial packing alone: two 1 mm spheres 0.1 mm apart (190 % of
// the radius overlap) and a third apart. dt = 1e-5 s is below the spring's critical step
// (2.3e-5 s), so the overlap alone is the cause; with dt "auto" (1.1e-6 s) the spring resolves
// even this and nothing blows up.
#include <filesystem>
#include <fstream>

namespace shard::test {

// Writes scene.toml and spheres.csv into `dir` (which must exist); returns the scene's path.
inline std::filesystem::path write_overlap_scene(const std::filesystem::path& dir) {
  std::ofstream(dir / "spheres.csv") << "x,y,z,r\n0,0,0.002,0.001\n0,0,0.0021,0.001\n0.004,0,0.002,0.001\n";
  std::ofstream(dir / "scene.toml") << R"([simulation]
duration = 0.001
dt = 1e-5
[material]
density = 2500
[generator]
plugin = "from_file"
spheres = "spheres.csv"
bonds = ""
max_overlap = 2.0
[contact]
plugin = "linear_spring"
normal_stiffness = 1e5
)";
  return dir / "scene.toml";
}

}  // namespace shard::test
