// Open edges of a welded mesh: covered by T-junctions (geometrically closed) or bordering a gap.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "shard/geometry/mesh_repair.hpp"

namespace shard::geometry {
namespace {

struct Edge {
  Index a, b;  // directed as its face traverses it
};

// Distance from p to the segment a-b, and the parameter of the nearest point (0 at a, 1 at b).
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, double& t) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

std::vector<Edge> open_edges_of(const TriangleMesh& mesh) {
  struct Uses {
    std::uint32_t count = 0;
    Edge first{};
  };
  std::unordered_map<std::uint64_t, Uses> edges;
  edges.reserve(mesh.faces.size() * 2);
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const Index a = f[k], b = f[(k + 1) % 3];
      const auto key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
      Uses& uses = edges[key];
      if (uses.count++ == 0) uses.first = Edge{a, b};
    }
  std::vector<Edge> open;
  for (const auto& [key, uses] : edges)
    if (uses.count == 1) open.push_back(uses.first);
  // The map's order is an implementation detail; the report must not depend on it.
  std::sort(open.begin(), open.end(), [](const Edge& x, const Edge& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  return open;
}

// Uniform grid over the open edges: each edge is listed in every cell that a point within
// `margin` of it can lie in, so the edges within `margin` of a point are all listed in the point's
// cell. An edge is walked along its length (not by its bounding box, whose cell count grows with
// the cube of its length): O(length / cell) cells per edge.
class EdgeGrid {
 public:
  EdgeGrid(const TriangleMesh& mesh, const std::vector<Edge>& edges, double cell, double margin)
      : cell_(cell), origin_(bounding_box(mesh).lower - Vec3::Constant(margin + 2.0 * cell)) {
    for (std::size_t e = 0; e < edges.size(); ++e)
      along(mesh.vertices[edges[e].a], mesh.vertices[edges[e].b], margin, [&](std::uint64_t key) { cells_[key].push_back(e); });
  }
  // Calls visit(edge index) for the edges listed in the cells along the segment a-b; an edge can
  // come more than once.
  template <class Visit>
  void edges_along(const Vec3& a, const Vec3& b, Visit&& visit) const {
    along(a, b, 0.0, [&](std::uint64_t key) { visit_cell(key, visit); });
  }
  // The same for the cells of the box [lo, hi] (a few cells: the box is at most a cell wide).
  template <class Visit>
  void edges_in_box(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    for_box(lo, hi, [&](std::uint64_t key) { visit_cell(key, visit); });
  }

 private:
  template <class Visit>
  void visit_cell(std::uint64_t key, Visit& visit) const {
    if (const auto it = cells_.find(key); it != cells_.end())
      for (std::size_t e : it->second) visit(e);
  }
  // The cells within `margin` of the segment, each once: boxes of half-width margin + step / 2
  // around points `step` <= cell apart cover every point within `margin` of the segment.
  template <class Visit>
  void along(const Vec3& a, const Vec3& b, double margin, Visit&& visit) const {
    const double length = (b - a).norm();
    const auto steps = static_cast<std::size_t>(std::ceil(length / cell_));
    const double reach = margin + 0.5 * (steps > 0 ? length / static_cast<double>(steps) : 0.0);
    keys_.clear();
    for (std::size_t s = 0; s <= steps; ++s) {
      const Vec3 p = steps > 0 ? Vec3(a + (b - a) * (static_cast<double>(s) / static_cast<double>(steps))) : a;
      for_box(p - Vec3::Constant(reach), p + Vec3::Constant(reach), [&](std::uint64_t key) { keys_.push_back(key); });
    }
    std::sort(keys_.begin(), keys_.end());
    keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());
    for (std::uint64_t key : keys_) visit(key);
  }
  template <class Visit>
  void for_box(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    const Eigen::Array3d l = ((lo - origin_) / cell_).array().floor().max(0.0);
    const Eigen::Array3d h = ((hi - origin_) / cell_).array().floor().max(0.0);
    for (auto i = static_cast<std::uint64_t>(l.x()); i <= static_cast<std::uint64_t>(h.x()); ++i)
      for (auto j = static_cast<std::uint64_t>(l.y()); j <= static_cast<std::uint64_t>(h.y()); ++j)
        for (auto k = static_cast<std::uint64_t>(l.z()); k <= static_cast<std::uint64_t>(h.z()); ++k)
          visit(i | (j << 21) | (k << 42));
  }
  double cell_;
  Vec3 origin_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
  mutable std::vector<std::uint64_t> keys_;  // scratch of along(); the grid is used by one thread
};

Vec3 direction(const std::vector<Vec3>& v, const Edge& e) { return Vec3(v[e.b] - v[e.a]); }

// The open edges with the grid that finds them near a point, and the tolerance of "lying on".
struct OpenEdges {
  const std::vector<Vec3>& v;
  const std::vector<Edge>& edges;
  const EdgeGrid& grid;
  double tol;
};

// The open-edge vertices lying on edge e (within tol of it, not at its ends) with its own two
// ends, ordered along it: the stops between which its pieces run.
void stops_along(const OpenEdges& open, std::size_t e, std::vector<std::pair<double, Index>>& stops) {
  const auto& v = open.v;
  const auto& edges = open.edges;
  const Vec3& a = v[edges[e].a];
  const Vec3& b = v[edges[e].b];
  stops.assign({{0.0, edges[e].a}, {1.0, edges[e].b}});
  open.grid.edges_along(a, b, [&](std::size_t f) {
    for (Index w : {edges[f].a, edges[f].b}) {
      if (w == edges[e].a || w == edges[e].b) continue;
      double t = 0.0;
      if (segment_distance(v[w], a, b, t) <= open.tol && (v[w] - a).norm() > open.tol && (v[w] - b).norm() > open.tol)
        stops.emplace_back(t, w);
    }
  });
  std::sort(stops.begin(), stops.end());
  stops.erase(std::unique(stops.begin(), stops.end()), stops.end());
}

// Whether every piece of edge e between consecutive stops lies on an open edge running the other way.
bool all_pieces_covered(const OpenEdges& open, std::size_t e, const std::vector<std::pair<double, Index>>& stops) {
  const auto& v = open.v;
  const auto& edges = open.edges;
  bool all_pieces = true;
  for (std::size_t s = 0; s + 1 < stops.size() && all_pieces; ++s) {
    const Vec3& p = v[stops[s].second];
    const Vec3& q = v[stops[s + 1].second];
    bool piece = false;
    open.grid.edges_in_box(p, p, [&](std::size_t f) {
      if (piece || f == e || direction(v, edges[f]).dot(direction(v, edges[e])) >= 0.0) return;
      double t = 0.0;
      piece = segment_distance(p, v[edges[f].a], v[edges[f].b], t) <= open.tol &&
              segment_distance(q, v[edges[f].a], v[edges[f].b], t) <= open.tol;
    });
    all_pieces = piece;
  }
  return all_pieces;
}

// An open edge is covered when every piece between the open-edge vertices lying on it is lying
// on an open edge of the other side running the other way: a T-junction, closed as a surface.
// Fills the report's counts; returns which edges are covered.
std::vector<char> find_covered_edges(const OpenEdges& open, OpenEdgeReport& report) {
  std::vector<char> covered(open.edges.size(), 0);
  std::vector<char> on_an_edge(open.v.size(), 0);
  std::vector<std::pair<double, Index>> stops;
  for (std::size_t e = 0; e < open.edges.size(); ++e) {
    stops_along(open, e, stops);
    if (stops.size() > 2)
      for (std::size_t s = 1; s + 1 < stops.size(); ++s) on_an_edge[static_cast<std::size_t>(stops[s].second)] = 1;
    covered[e] = all_pieces_covered(open, e, stops) ? 1 : 0;
  }
  report.t_junctions = static_cast<std::size_t>(std::count(on_an_edge.begin(), on_an_edge.end(), 1));
  report.covered_edges = static_cast<std::size_t>(std::count(covered.begin(), covered.end(), 1));
  report.gap_edges = open.edges.size() - report.covered_edges;
  return covered;
}

// Width of each opening: from a gap edge's midpoint to the nearest open edge running the other
// way. Across a crack that is its width; the edges along a hole's border run the same way as
// their neighbours, so a finely cut hole still measures its diameter, not its edge length.
void measure_gaps(const OpenEdges& open, const std::vector<char>& covered, double gap_tolerance,
                  OpenEdgeReport& report) {
  const auto& v = open.v;
  const auto& edges = open.edges;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (covered[e]) continue;
    const Vec3 mid = 0.5 * (v[edges[e].a] + v[edges[e].b]);
    double width = std::numeric_limits<double>::infinity();
    open.grid.edges_in_box(mid - Vec3::Constant(gap_tolerance), mid + Vec3::Constant(gap_tolerance), [&](std::size_t f) {
      // Covered edges count as the far side too: a crack whose sides slide along each other is
      // covered in places, and the uncovered pieces next to them face the covered ones.
      if (f == e || direction(v, edges[f]).dot(direction(v, edges[e])) >= 0.0) return;
      double t = 0.0;
      width = std::min(width, segment_distance(mid, v[edges[f].a], v[edges[f].b], t));
    });
    if (width > gap_tolerance) {
      width = std::numeric_limits<double>::infinity();
      ++report.wide_gap_edges;
    }
    report.largest_gap = std::max(report.largest_gap, width);
  }
}

// The openings' share of the enclosed volume: a closed surface's area vectors sum to zero.
double volume_ambiguity(const TriangleMesh& mesh, double diagonal) {
  const auto& v = mesh.vertices;
  Vec3 area = Vec3::Zero();
  for (const auto& f : mesh.faces) area += 0.5 * (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]);
  const double volume = std::abs(signed_volume(mesh));
  return volume > 0.0 ? area.norm() * diagonal / (3.0 * volume) : std::numeric_limits<double>::infinity();
}

}  // namespace

OpenEdgeReport classify_open_edges(const TriangleMesh& mesh, double on_edge_tolerance, double gap_tolerance) {
  OpenEdgeReport report;
  const std::vector<Edge> edges = open_edges_of(mesh);
  report.open_edges = edges.size();
  if (edges.empty()) return report;
  const auto& v = mesh.vertices;
  const Box box = bounding_box(mesh);
  const double diagonal = (box.upper - box.lower).norm();
  const double tol = std::max(on_edge_tolerance, 0.0);
  double mean_length = 0.0;
  for (const Edge& e : edges) mean_length += (v[e.b] - v[e.a]).norm();
  mean_length /= static_cast<double>(edges.size());
  // At least 1/1024 of the diagonal keeps the cell index within 21 bits per axis.
  const double cell = std::max({mean_length, 2.0 * tol, gap_tolerance, diagonal / 1024.0, 1e-300});
  const EdgeGrid grid(mesh, edges, cell, tol);
  const OpenEdges open{v, edges, grid, tol};

  const std::vector<char> covered = find_covered_edges(open, report);
  if (report.gap_edges == 0) return report;
  measure_gaps(open, covered, gap_tolerance, report);
  report.volume_ambiguity = volume_ambiguity(mesh, diagonal);
  return report;
}

}  // namespace shard::geometry
