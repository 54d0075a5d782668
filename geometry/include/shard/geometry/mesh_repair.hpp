#pragma once
// The small defects CAD exporters and scanners leave in a closed body, and their repair:
//  - seam vertices that differ in the last bits of their float32 coordinates (the exporter
//    computed the same corner twice): welded within a tolerance;
//  - T-junctions, a vertex lying on an edge of the neighbouring face instead of being one of its
//    corners: the surface is geometrically closed, only its edge list is not;
//  - cracks narrower than a gap tolerance.
// A truly open body (a missing face) keeps being refused by require_closed_solid().
#include <cstddef>
#include <filesystem>
#include <string>

#include "shard/geometry/stl.hpp"

namespace shard::geometry {

// 1e-6 of the bounding-box diagonal, and at least 8 float32 units in the last place of the
// largest coordinate. float32 resolves 6e-8 of a coordinate, so a seam computed twice differs by
// a few units in the last place; 1e-6 of the body's size is ~16 of them for a body at the origin,
// and the floor covers a body placed far from it. Two distinct corners that close would need
// a million edges along the body: no real mesh is that fine.
double default_weld_tolerance(const TriangleMesh& mesh);

struct WeldReport {
  std::size_t vertices_welded = 0;  // vertices merged into an earlier one
  std::size_t faces_dropped = 0;    // faces that collapsed to a line or a point
};

// Merges every vertex into the first earlier vertex within `tolerance` [m] (a spatial hash of
// cell `tolerance`: O(vertices)); faces that collapse are dropped. Vertex order and indices are
// kept: a mesh with nothing to weld is returned unchanged bit for bit. tolerance <= 0 welds nothing.
WeldReport weld_vertices(TriangleMesh& mesh, double tolerance);

struct OpenEdgeReport {
  std::size_t open_edges = 0;     // edges used by one face only
  std::size_t t_junctions = 0;    // vertices lying inside an open edge (within the on-edge tolerance)
  std::size_t covered_edges = 0;  // open edges covered by collinear open edges running the other way
  std::size_t gap_edges = 0;      // open edges that are not covered: the border of a crack or a hole
  // Widest opening [m]: for each gap edge, the distance from its midpoint to the nearest open edge
  // running the other way (across a crack: its width; across a hole: its diameter). Infinity when
  // some gap edge has no such edge within the gap tolerance.
  double largest_gap = 0.0;
  std::size_t wide_gap_edges = 0;  // gap edges with no such edge within the gap tolerance
  // Largest change of the enclosed (divergence-theorem) volume with the reference point, relative
  // to the volume: |sum of face area vectors| x bounding-box diagonal / (3 V). 0 for a closed
  // surface; it bounds how much the openings leave inside and outside undecided.
  double volume_ambiguity = 0.0;
  bool geometrically_closed() const { return gap_edges == 0; }
};

// Classifies the open edges: T-junction covered, or bordering a gap (measured up to
// `gap_tolerance` [m]). `on_edge_tolerance` [m]: how far a vertex may lie from an edge and still
// be on it (the weld tolerance). Spatial grid over the open edges: about O(open edges).
OpenEdgeReport classify_open_edges(const TriangleMesh& mesh, double on_edge_tolerance, double gap_tolerance);

// Tolerances of the closed-solid check [m]; 0 selects the default.
struct SolidTolerances {
  double weld = 0.0;  // default_weld_tolerance()
  double gap = 0.0;   // kDefaultRelativeGap x bounding-box diagonal
};
// Default gap tolerance relative to the bounding-box diagonal: 1e-3 of the body's size is far below
// what a packing resolves (stl_fill also caps it at the smallest sphere's radius: no sphere passes
// through a crack narrower than that). Many narrow cracks can still add up: they are accepted only while
// volume_ambiguity stays below kMaxVolumeAmbiguity.
inline constexpr double kDefaultRelativeGap = 1e-3;
inline constexpr double kMaxVolumeAmbiguity = 1e-3;

struct SolidRepair {
  double weld_tolerance = 0.0;  // [m] used
  double gap_tolerance = 0.0;   // [m] used
  WeldReport weld;
  OpenEdgeReport edges;
  // Nothing to repair: every edge in exactly two faces before and after welding.
  bool untouched() const { return weld.vertices_welded == 0 && weld.faces_dropped == 0 && edges.open_edges == 0; }
  // One line for the generator's log: what was repaired.
  std::string summary() const;
};

// require_closed_solid() with explicit tolerances (`mesh` as it is, not welded): open edges are
// accepted when T-junctions cover them, or when every opening is narrower than the gap tolerance
// and leaves less than kMaxVolumeAmbiguity of the volume undecided. Returns the open-edge report.
OpenEdgeReport require_closed_solid(const TriangleMesh& mesh, const std::filesystem::path& file,
                                    SolidTolerances tolerances);

// Welds `mesh` and runs require_closed_solid() on it with the same tolerances; returns what was
// repaired. Throws StlError naming `file` like require_closed_solid().
SolidRepair repair_closed_solid(TriangleMesh& mesh, const std::filesystem::path& file, SolidTolerances tolerances = {});

}  // namespace shard::geometry
