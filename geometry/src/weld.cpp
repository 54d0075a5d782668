// Welding of vertices that lie within a tolerance of each other (seams written twice).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "shard/geometry/mesh_repair.hpp"

namespace shard::geometry {
namespace {

struct CellKey {
  std::int64_t i, j, k;
  bool operator==(const CellKey&) const = default;
};

struct CellKeyHash {
  std::size_t operator()(const CellKey& c) const {
    std::uint64_t h = static_cast<std::uint64_t>(c.i);
    h = h * 0x9E3779B97F4A7C15ULL ^ static_cast<std::uint64_t>(c.j);
    h = h * 0x9E3779B97F4A7C15ULL ^ static_cast<std::uint64_t>(c.k);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

}  // namespace

double default_weld_tolerance(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return 0.0;
  const Box box = bounding_box(mesh);
  const double largest = std::max(box.lower.cwiseAbs().maxCoeff(), box.upper.cwiseAbs().maxCoeff());
  const double float32_ulp = std::ldexp(largest, -23);  // float32: 24-bit significand
  return std::max(1e-6 * (box.upper - box.lower).norm(), 8.0 * float32_ulp);
}

WeldReport weld_vertices(TriangleMesh& mesh, double tolerance) {
  WeldReport report;
  if (!(tolerance > 0.0) || mesh.vertices.empty()) return report;
  const Box box = bounding_box(mesh);
  const Vec3 origin = box.lower;
  // Cells no smaller than 1e-12 of the body keep the cell index far inside int64 for any tolerance;
  // a larger cell than the tolerance only makes the 27 cells hold more candidates.
  const double cell = std::max(tolerance, 1e-12 * (box.upper - box.lower).norm());
  auto cell_of = [&](const Vec3& p) {
    const Vec3 c = ((p - origin) / cell).array().floor();
    return CellKey{static_cast<std::int64_t>(c.x()), static_cast<std::int64_t>(c.y()), static_cast<std::int64_t>(c.z())};
  };
  // The cells hold the kept vertices; a vertex within `tolerance` (<= cell) of a kept one lies in
  // one of the 27 cells around its own.
  std::unordered_map<CellKey, std::vector<Index>, CellKeyHash> cells;
  cells.reserve(mesh.vertices.size());
  std::vector<Index> new_index(mesh.vertices.size());
  std::vector<Vec3> kept;
  kept.reserve(mesh.vertices.size());
  const double tolerance2 = tolerance * tolerance;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Vec3& p = mesh.vertices[v];
    const CellKey home = cell_of(p);
    Index nearest = std::numeric_limits<Index>::max();
    double nearest2 = tolerance2;
    for (std::int64_t di = -1; di <= 1; ++di)
      for (std::int64_t dj = -1; dj <= 1; ++dj)
        for (std::int64_t dk = -1; dk <= 1; ++dk) {
          const auto it = cells.find(CellKey{home.i + di, home.j + dj, home.k + dk});
          if (it == cells.end()) continue;
          for (Index k : it->second) {
            const double d2 = (kept[static_cast<std::size_t>(k)] - p).squaredNorm();
            if (d2 <= nearest2 && (d2 < nearest2 || k < nearest)) {
              nearest2 = d2;
              nearest = k;
            }
          }
        }
    if (nearest != std::numeric_limits<Index>::max()) {
      new_index[v] = nearest;
      ++report.vertices_welded;
    } else {
      new_index[v] = static_cast<Index>(kept.size());
      cells[home].push_back(new_index[v]);
      kept.push_back(p);
    }
  }
  if (report.vertices_welded == 0) return report;
  mesh.vertices = std::move(kept);
  std::vector<std::array<Index, 3>> faces;
  faces.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    const std::array<Index, 3> g{new_index[static_cast<std::size_t>(f[0])], new_index[static_cast<std::size_t>(f[1])],
                                 new_index[static_cast<std::size_t>(f[2])]};
    if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) {
      ++report.faces_dropped;
      continue;
    }
    faces.push_back(g);
  }
  mesh.faces = std::move(faces);
  return report;
}

}  // namespace shard::geometry
