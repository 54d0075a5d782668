// Self-intersection test of a triangle mesh: does an edge of one face pierce another face?
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "shard/geometry/stl.hpp"

namespace shard::geometry {
namespace {

// Segment p-q crosses the interior of triangle a-b-c (Moller-Trumbore with strict bounds).
// `eps` keeps touching configurations (an edge ending on the face) from counting.
bool segment_pierces_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c,
                              double eps) {
  const Vec3 dir = q - p;
  const Vec3 e1 = b - a;
  const Vec3 e2 = c - a;
  const Vec3 h = dir.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) <= 1e-14 * e1.norm() * e2.norm() * dir.norm()) return false;  // parallel
  const double inv = 1.0 / det;
  const Vec3 s = p - a;
  const double u = inv * s.dot(h);
  if (u <= eps || u >= 1.0 - eps) return false;
  const Vec3 qv = s.cross(e1);
  const double v = inv * dir.dot(qv);
  if (v <= eps || u + v >= 1.0 - eps) return false;
  const double t = inv * e2.dot(qv);
  return t > eps && t < 1.0 - eps;
}

bool faces_cross(const TriangleMesh& mesh, const std::array<Index, 3>& f, const std::array<Index, 3>& g) {
  for (Index x : f)
    for (Index y : g)
      if (x == y) return false;  // neighbours touch by construction
  constexpr double eps = 1e-9;
  const auto& v = mesh.vertices;
  for (int k = 0; k < 3; ++k) {
    if (segment_pierces_triangle(v[f[k]], v[f[(k + 1) % 3]], v[g[0]], v[g[1]], v[g[2]], eps)) return true;
    if (segment_pierces_triangle(v[g[k]], v[g[(k + 1) % 3]], v[f[0]], v[f[1]], v[f[2]], eps)) return true;
  }
  return false;
}

}  // namespace

std::size_t count_self_intersections(const TriangleMesh& mesh, std::size_t stop_after) {
  if (mesh.faces.size() < 2) return 0;
  const Box box = bounding_box(mesh);
  // Cell size: the mean face extent, so a face touches a few cells.
  double mean_extent = 0.0;
  for (const auto& f : mesh.faces) {
    const Vec3 lo = mesh.vertices[f[0]].cwiseMin(mesh.vertices[f[1]]).cwiseMin(mesh.vertices[f[2]]);
    const Vec3 hi = mesh.vertices[f[0]].cwiseMax(mesh.vertices[f[1]]).cwiseMax(mesh.vertices[f[2]]);
    mean_extent += (hi - lo).maxCoeff();
  }
  mean_extent /= static_cast<double>(mesh.faces.size());
  const double diag = (box.upper - box.lower).maxCoeff();
  const double cell = std::max({mean_extent, diag / 512.0, 1e-300});
  auto cell_of = [&](double x, int axis) {
    return static_cast<std::int64_t>(std::floor((x - box.lower[axis]) / cell));
  };
  auto key_of = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return static_cast<std::uint64_t>(i) | (static_cast<std::uint64_t>(j) << 21) |
           (static_cast<std::uint64_t>(k) << 42);
  };
  std::unordered_map<std::uint64_t, std::vector<Index>> cells;
  std::vector<std::pair<Index, Index>> candidates;
  for (Index t = 0; t < static_cast<Index>(mesh.faces.size()); ++t) {
    const auto& f = mesh.faces[t];
    const Vec3 lo = mesh.vertices[f[0]].cwiseMin(mesh.vertices[f[1]]).cwiseMin(mesh.vertices[f[2]]);
    const Vec3 hi = mesh.vertices[f[0]].cwiseMax(mesh.vertices[f[1]]).cwiseMax(mesh.vertices[f[2]]);
    for (std::int64_t i = cell_of(lo.x(), 0); i <= cell_of(hi.x(), 0); ++i)
      for (std::int64_t j = cell_of(lo.y(), 1); j <= cell_of(hi.y(), 1); ++j)
        for (std::int64_t k = cell_of(lo.z(), 2); k <= cell_of(hi.z(), 2); ++k) {
          auto& list = cells[key_of(i, j, k)];
          for (Index other : list) candidates.emplace_back(other, t);
          list.push_back(t);
        }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  std::size_t crossings = 0;
  for (const auto& [a, b] : candidates) {
    if (faces_cross(mesh, mesh.faces[a], mesh.faces[b]) && ++crossings >= stop_after) break;
  }
  return crossings;
}

}  // namespace shard::geometry
