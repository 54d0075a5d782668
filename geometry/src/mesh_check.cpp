// Watertightness, orientation and volume of a triangle mesh.
#include <fmt/core.h>

#include <algorithm>
#include <limits>
#include <cstdint>
#include <unordered_map>

#include "shard/geometry/mesh_repair.hpp"
#include "shard/geometry/stl.hpp"

namespace shard::geometry {

double signed_volume(const TriangleMesh& mesh) {
  // Sum of tetrahedra (origin, a, b, c); the origin is moved to the first vertex to limit
  // cancellation for bodies far from the origin.
  if (mesh.vertices.empty()) return 0.0;
  const Vec3 origin = mesh.vertices.front();
  double six_volume = 0.0;
  for (const auto& f : mesh.faces) {
    const Vec3 a = mesh.vertices[f[0]] - origin;
    const Vec3 b = mesh.vertices[f[1]] - origin;
    const Vec3 c = mesh.vertices[f[2]] - origin;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

MeshReport inspect_mesh(const TriangleMesh& mesh) {
  // Each undirected edge counts its uses in both directions; a closed, consistently oriented
  // surface uses every edge exactly once each way.
  struct Uses {
    std::uint32_t forward = 0;   // traversed from the smaller to the larger vertex index
    std::uint32_t backward = 0;
  };
  std::unordered_map<std::uint64_t, Uses> edges;
  edges.reserve(mesh.faces.size() * 2);
  for (const auto& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const Index a = f[k];
      const Index b = f[(k + 1) % 3];
      const auto lo = static_cast<std::uint64_t>(std::min(a, b));
      const auto hi = static_cast<std::uint64_t>(std::max(a, b));
      Uses& uses = edges[(lo << 32) | hi];
      (a < b ? uses.forward : uses.backward) += 1;
    }
  }
  MeshReport report;
  for (const auto& [key, uses] : edges) {
    const std::uint32_t total = uses.forward + uses.backward;
    if (total == 1) ++report.open_edges;
    else if (total > 2) ++report.nonmanifold_edges;
    else if (uses.forward != 1) ++report.misoriented_edges;
  }
  report.signed_volume = signed_volume(mesh);
  return report;
}

Box bounding_box(const TriangleMesh& mesh) {
  Box box{Vec3::Constant(std::numeric_limits<double>::infinity()),
          Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (const Vec3& v : mesh.vertices) {
    box.lower = box.lower.cwiseMin(v);
    box.upper = box.upper.cwiseMax(v);
  }
  return box;
}

void require_closed_solid(const TriangleMesh& mesh, const std::filesystem::path& file) {
  require_closed_solid(mesh, file, SolidTolerances{});
}

OpenEdgeReport require_closed_solid(const TriangleMesh& mesh, const std::filesystem::path& file,
                                    SolidTolerances tolerances) {
  const std::string name = file.string();
  if (mesh.faces.empty())
    throw StlError(fmt::format("STL file '{}' has no triangles: export the body as a closed surface", name));
  const MeshReport report = inspect_mesh(mesh);
  OpenEdgeReport edges;
  if (report.open_edges > 0) {
    const Box box = bounding_box(mesh);
    const double weld = tolerances.weld > 0.0 ? tolerances.weld : default_weld_tolerance(mesh);
    const double gap = tolerances.gap > 0.0 ? tolerances.gap : kDefaultRelativeGap * (box.upper - box.lower).norm();
    edges = classify_open_edges(mesh, weld, gap);
    if (!edges.geometrically_closed() && !(edges.largest_gap <= gap))
      throw StlError(fmt::format("STL file '{}' is not closed: {} open edges (holes in the surface; {} of them "
                                 "border openings wider than the gap tolerance {:.3g} m). A body to fill must be "
                                 "watertight; close the holes (e.g. MeshLab 'Close Holes' or re-export as a solid)",
                                 name, report.open_edges, edges.wide_gap_edges, gap));
    if (!edges.geometrically_closed() && !(edges.volume_ambiguity <= kMaxVolumeAmbiguity))
      throw StlError(fmt::format("STL file '{}' is not closed: {} open edges border cracks at most {:.3g} m wide, "
                                 "but together they leave {:.2g} % of the volume undecided (limit {:.2g} %). Close "
                                 "the cracks (e.g. MeshLab 'Close Holes' or re-export as a solid)",
                                 name, report.open_edges, edges.largest_gap, 100.0 * edges.volume_ambiguity,
                                 100.0 * kMaxVolumeAmbiguity));
  }
  if (report.nonmanifold_edges > 0)
    throw StlError(fmt::format("STL file '{}' is not closed: {} non-manifold edges (shared by more than "
                               "two faces). Separate or union the touching parts before filling",
                               name, report.nonmanifold_edges));
  if (report.misoriented_edges > 0)
    throw StlError(fmt::format("STL file '{}' has inconsistently oriented faces: {} edges are traversed "
                               "twice in the same direction. Re-orient the faces coherently (e.g. "
                               "MeshLab 'Re-Orient all faces coherently')",
                               name, report.misoriented_edges));
  if (!(report.signed_volume > 0.0))
    throw StlError(fmt::format("STL file '{}' has inverted normals (signed volume {:.6g} <= 0): the "
                               "faces point inward. Flip the face orientation (e.g. MeshLab 'Invert "
                               "Faces Orientation')",
                               name, report.signed_volume));
  if (const std::size_t crossings = count_self_intersections(mesh); crossings > 0)
    throw StlError(fmt::format("STL file '{}' is self-intersecting: faces cross each other (first "
                               "crossing found). Merge overlapping parts with a boolean union before "
                               "filling",
                               name));
  return edges;
}

}  // namespace shard::geometry
