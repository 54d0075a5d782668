// libFuzzer target: any byte string read as an STL file either gives a mesh that the checks
// (welding, closedness with T-junctions and gaps, orientation, volume, self-intersection) can inspect, or throws StlError.
// read_stl takes a path, so each input is written to a per-process temporary file.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "shard/geometry/mesh_repair.hpp"
#include "shard/geometry/stl.hpp"

namespace {

std::filesystem::path scratch_file() {
  return std::filesystem::temp_directory_path() / ("shard_fuzz_stl_" + std::to_string(getpid()) + ".stl");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = scratch_file();
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const shard::geometry::TriangleMesh mesh = shard::geometry::read_stl(file, 1.0);
    const shard::geometry::MeshReport report = shard::geometry::inspect_mesh(mesh);
    (void)report;
    (void)shard::geometry::count_self_intersections(mesh, 4);
    if (!mesh.vertices.empty()) (void)shard::geometry::bounding_box(mesh);
    // What stl_fill and from_file run: weld, then the closed-solid checks (T-junctions, cracks).
    shard::geometry::TriangleMesh welded = mesh;
    (void)shard::geometry::repair_closed_solid(welded, file);
  } catch (const shard::geometry::StlError&) {
  }
  return 0;
}
