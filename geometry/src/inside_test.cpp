#include "shard/geometry/inside_test.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace shard::geometry {

double winding_number(const TriangleMesh& mesh, const Vec3& point) {
  double solid_angle = 0.0;
  for (const auto& f : mesh.faces) {
    const Vec3 a = mesh.vertices[f[0]] - point;
    const Vec3 b = mesh.vertices[f[1]] - point;
    const Vec3 c = mesh.vertices[f[2]] - point;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    // tan(Omega / 2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|)
    solid_angle += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return solid_angle / (4.0 * std::numbers::pi);
}

InsideTest::InsideTest(const TriangleMesh& mesh, SignRule rule) : mesh_(mesh), rule_(rule) {
  const Box box = bounding_box(mesh);
  const int n = std::clamp(static_cast<int>(2.0 * std::sqrt(static_cast<double>(mesh.faces.size()))), 1, 512);
  for (int axis = 0; axis < 3; ++axis) {
    AxisGrid& g = grids_[axis];
    g.axis = axis;
    g.u = (axis + 1) % 3;
    g.v = (axis + 2) % 3;
    g.n = n;
    g.lo_u = box.lower[g.u];
    g.lo_v = box.lower[g.v];
    g.cell_u = std::max((box.upper[g.u] - box.lower[g.u]) / n, 1e-300);
    g.cell_v = std::max((box.upper[g.v] - box.lower[g.v]) / n, 1e-300);
    auto bucket_range = [&](const std::array<Index, 3>& f, int& u0, int& u1, int& v0, int& v1) {
      double umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300;
      for (Index k : f) {
        umin = std::min(umin, mesh.vertices[k][g.u]);
        umax = std::max(umax, mesh.vertices[k][g.u]);
        vmin = std::min(vmin, mesh.vertices[k][g.v]);
        vmax = std::max(vmax, mesh.vertices[k][g.v]);
      }
      u0 = std::clamp(static_cast<int>(std::floor((umin - g.lo_u) / g.cell_u)), 0, n - 1);
      u1 = std::clamp(static_cast<int>(std::floor((umax - g.lo_u) / g.cell_u)), 0, n - 1);
      v0 = std::clamp(static_cast<int>(std::floor((vmin - g.lo_v) / g.cell_v)), 0, n - 1);
      v1 = std::clamp(static_cast<int>(std::floor((vmax - g.lo_v) / g.cell_v)), 0, n - 1);
    };
    std::vector<int> count(static_cast<std::size_t>(n * n) + 1, 0);
    for (const auto& f : mesh.faces) {
      int u0, u1, v0, v1;
      bucket_range(f, u0, u1, v0, v1);
      for (int a = u0; a <= u1; ++a)
        for (int b = v0; b <= v1; ++b) ++count[static_cast<std::size_t>(a * n + b) + 1];
    }
    for (std::size_t b = 1; b < count.size(); ++b) count[b] += count[b - 1];
    g.start = count;
    g.faces.assign(static_cast<std::size_t>(count.back()), 0);
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (Index t = 0; t < static_cast<Index>(mesh.faces.size()); ++t) {
      int u0, u1, v0, v1;
      bucket_range(mesh.faces[t], u0, u1, v0, v1);
      for (int a = u0; a <= u1; ++a)
        for (int b = v0; b <= v1; ++b) g.faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(a * n + b)]++)] = t;
    }
  }
}

bool InsideTest::odd_crossings(const AxisGrid& g, const Vec3& p) const {
  // A tiny irrational shift of the ray keeps it off the edges and diagonals of meshes with
  // round-number coordinates (a ray through a cube's centre would hit face diagonals exactly).
  const double pu = p[g.u] + 0.41421356237 * 1e-9 * g.cell_u * g.n;
  const double pv = p[g.v] + 0.73205080757 * 1e-9 * g.cell_v * g.n;
  const int a = static_cast<int>(std::floor((pu - g.lo_u) / g.cell_u));
  const int b = static_cast<int>(std::floor((pv - g.lo_v) / g.cell_v));
  if (a < 0 || b < 0 || a >= g.n || b >= g.n) return false;
  const auto bucket = static_cast<std::size_t>(a * g.n + b);
  bool odd = false;
  for (int k = g.start[bucket]; k < g.start[bucket + 1]; ++k) {
    const auto& f = mesh_.faces[g.faces[static_cast<std::size_t>(k)]];
    const Vec3& A = mesh_.vertices[f[0]];
    const Vec3& B = mesh_.vertices[f[1]];
    const Vec3& C = mesh_.vertices[f[2]];
    // 2D barycentric test of (pu, pv) in the projected triangle.
    const double d = (B[g.u] - A[g.u]) * (C[g.v] - A[g.v]) - (C[g.u] - A[g.u]) * (B[g.v] - A[g.v]);
    if (d == 0.0) continue;  // face parallel to the ray
    const double s = ((pu - A[g.u]) * (C[g.v] - A[g.v]) - (C[g.u] - A[g.u]) * (pv - A[g.v])) / d;
    const double t = ((B[g.u] - A[g.u]) * (pv - A[g.v]) - (pu - A[g.u]) * (B[g.v] - A[g.v])) / d;
    if (s < 0.0 || t < 0.0 || s + t >= 1.0 || (s == 0.0 && t == 0.0)) continue;
    const double hit = A[g.axis] + s * (B[g.axis] - A[g.axis]) + t * (C[g.axis] - A[g.axis]);
    if (hit > p[g.axis]) odd = !odd;
  }
  return odd;
}

bool InsideTest::inside(const Vec3& point) const {
  int votes = 0;
  for (const AxisGrid& g : grids_) votes += odd_crossings(g, point) ? 1 : 0;
  // Rays agree everywhere except next to a crack or a T-junction seam, so the O(faces) winding
  // number is evaluated at few points.
  if (rule_ == SignRule::WindingWhenRaysDisagree && votes != 0 && votes != 3)
    return winding_number(mesh_, point) >= 0.5;
  return votes >= 2;
}

}  // namespace shard::geometry
