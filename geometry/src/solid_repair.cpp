// Weld, then check: a body as CAD exporters and scanners write it, made fit to fill.
#include <fmt/core.h>

#include "shard/geometry/mesh_repair.hpp"

namespace shard::geometry {

SolidRepair repair_closed_solid(TriangleMesh& mesh, const std::filesystem::path& file, SolidTolerances tolerances) {
  SolidRepair repair;
  const Box box = bounding_box(mesh);
  repair.weld_tolerance = tolerances.weld > 0.0 ? tolerances.weld : default_weld_tolerance(mesh);
  repair.gap_tolerance = tolerances.gap > 0.0 ? tolerances.gap : kDefaultRelativeGap * (box.upper - box.lower).norm();
  const std::size_t faces_read = mesh.faces.size();
  repair.weld = weld_vertices(mesh, repair.weld_tolerance);
  // Collapsed faces are slivers at the default tolerance; a tolerance near the size of the body's
  // features collapses most of it, and the body would be refused for holes it does not have.
  if (repair.weld.faces_dropped * 10 > faces_read)
    throw StlError(fmt::format("STL file '{}': welding vertices closer than {:.3g} m collapsed {} of its {} faces: "
                               "the weld tolerance is not small against the body's edges. Lower weld_tolerance "
                               "(0 selects 1e-6 of the body's size)",
                               file.string(), repair.weld_tolerance, repair.weld.faces_dropped, faces_read));
  repair.edges = require_closed_solid(mesh, file, SolidTolerances{repair.weld_tolerance, repair.gap_tolerance});
  return repair;
}

std::string SolidRepair::summary() const {
  if (untouched()) return "closed as read, nothing to repair";
  std::string line = fmt::format("{} vertices welded (tolerance {:.3g} m), {} collapsed faces dropped",
                                 weld.vertices_welded, weld_tolerance, weld.faces_dropped);
  if (edges.open_edges == 0) return line + ", closed after welding";
  line += fmt::format(", {} open edges: {} covered by {} T-junction vertices", edges.open_edges, edges.covered_edges,
                      edges.t_junctions);
  if (edges.geometrically_closed()) return line + " (geometrically closed)";
  return line + fmt::format(", {} bordering cracks; warning: largest gap {:.3g} m (tolerance {:.3g} m), "
                            "{:.2g} % of the volume undecided; inside/outside from the winding number",
                            edges.gap_edges, edges.largest_gap, gap_tolerance, 100.0 * edges.volume_ambiguity);
}

}  // namespace shard::geometry
