// Weld, then check: a body as CAD exporters and scanners write it, made fit to fill.
#include <fmt/core.h>

#include <cmath>

#include "shard/geometry/mesh_repair.hpp"

namespace shard::geometry {

SolidRepair repair_closed_solid(TriangleMesh& mesh, const std::filesystem::path& file, SolidTolerances tolerances) {
  SolidRepair repair;
  const Box box = bounding_box(mesh);
  repair.weld_tolerance = tolerances.weld > 0.0 ? tolerances.weld : default_weld_tolerance(mesh);
  repair.gap_tolerance = tolerances.gap > 0.0 ? tolerances.gap : kDefaultRelativeGap * (box.upper - box.lower).norm();
  repair.weld = weld_vertices(mesh, repair.weld_tolerance);
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
