#pragma once
// Small meshes built in code for the STL and generator tests.
#include <filesystem>
#include <string>

#include "shard/geometry/stl.hpp"

namespace shard::test {

// Axis-aligned box [lo, hi], outward normals, 12 triangles.
inline geometry::TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  geometry::TriangleMesh m;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) m.vertices.emplace_back(x ? hi.x() : lo.x(), y ? hi.y() : lo.y(), z ? hi.z() : lo.z());
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

inline geometry::TriangleMesh merged(const geometry::TriangleMesh& a, const geometry::TriangleMesh& b) {
  geometry::TriangleMesh m = a;
  const auto base = static_cast<Index>(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto f : b.faces) m.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  return m;
}

// A fresh folder per test run under the build tree's working directory.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::current_path() / ("scratch_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string geometry_dir() { return std::string(SHARD_SOURCE_DIR) + "/scenes/geometry"; }

}  // namespace shard::test
