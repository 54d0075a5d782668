#pragma once
// Small meshes built in code for the STL and generator tests.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

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

// Torus around the z axis (tube centre radius R, tube radius r; n_u segments around the axis,
// n_v around the tube) as a CAD exporter writes it: the seam column and row are separate vertices
// that should coincide with the first ones. With `last_bits`, each seam vertex is its partner's
// float32 coordinates moved by 1 (column seam), 2 (row seam) or 3 (the corner) float32 units in the
// last place (the exporter computed them twice); `seam_shift` moves them in +x (a real crack).
// Outward normals.
inline geometry::TriangleMesh seamed_torus(double R, double r, int n_u, int n_v, bool last_bits, double seam_shift = 0.0) {
  geometry::TriangleMesh m;
  auto id = [&](int i, int j) { return static_cast<Index>(i * (n_v + 1) + j); };
  for (int i = 0; i <= n_u; ++i)
    for (int j = 0; j <= n_v; ++j) {
      const double u = 2.0 * std::numbers::pi * (i % n_u) / n_u;
      const double v = 2.0 * std::numbers::pi * (j % n_v) / n_v;
      Vec3 p((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
      for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(p[k]);  // what the file holds
      if (i == n_u || j == n_v) {
        const int ulps = last_bits ? (i == n_u ? 1 : 0) + (j == n_v ? 2 : 0) : 0;
        for (int k = 0; k < 3; ++k) {
          auto f = static_cast<float>(p[k]);
          for (int step = 0; step < ulps; ++step) f = std::nextafter(f, 1e30f);
          p[k] = f;
        }
        p.x() += seam_shift;
      }
      m.vertices.push_back(p);
    }
  // (u, v) runs counter-clockwise seen from outside: du x dv points out of the tube.
  for (int i = 0; i < n_u; ++i)
    for (int j = 0; j < n_v; ++j) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

// L-shaped prism: the polygon (0,0) (20,0) (20,10) (10,10) (10,20) (0,20), z from 0 to 10. Each cap
// is three squares. With `t_junctions` each wall is one quad, so the caps' corners (10,0) and (0,10)
// lie on the middle of the long walls' edges: four T-junctions, twelve open edges, geometrically
// closed. Without, the long walls are split there: the same solid, conforming.
inline geometry::TriangleMesh l_prism(bool t_junctions) {
  geometry::TriangleMesh m;
  std::vector<std::array<double, 2>> outline{{0, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}};
  if (!t_junctions) outline = {{0, 0}, {10, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}, {0, 10}};
  auto vertex = [&](double x, double y, double z) {
    for (std::size_t k = 0; k < m.vertices.size(); ++k)
      if (m.vertices[k] == Vec3(x, y, z)) return static_cast<Index>(k);
    m.vertices.emplace_back(x, y, z);
    return static_cast<Index>(m.vertices.size() - 1);
  };
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const auto& c = outline[k];
    const auto& n = outline[(k + 1) % outline.size()];
    const Index a = vertex(c[0], c[1], 0), b = vertex(n[0], n[1], 0), bt = vertex(n[0], n[1], 10), at = vertex(c[0], c[1], 10);
    m.faces.push_back({a, b, bt});
    m.faces.push_back({a, bt, at});
  }
  const double squares[3][4][2] = {{{0, 0}, {10, 0}, {10, 10}, {0, 10}},     // counter-clockwise from +z
                                   {{10, 0}, {20, 0}, {20, 10}, {10, 10}},
                                   {{0, 10}, {10, 10}, {10, 20}, {0, 20}}};
  for (double z : {0.0, 10.0})
    for (const auto& sq : squares) {
      std::array<Index, 4> q{};
      for (int k = 0; k < 4; ++k) q[static_cast<std::size_t>(k)] = vertex(sq[k][0], sq[k][1], z);
      if (z > 0) {
        m.faces.push_back({q[0], q[1], q[2]});
        m.faces.push_back({q[0], q[2], q[3]});
      } else {  // the bottom cap faces -z
        m.faces.push_back({q[0], q[2], q[1]});
        m.faces.push_back({q[0], q[3], q[2]});
      }
    }
  return m;
}

// Distance from (x, y) to the outline of l_prism(): positive inside, negative outside.
inline double l_outline_inside_distance(double x, double y) {
  const double outline[6][2] = {{0, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}};
  double d = 1e300;
  for (int k = 0; k < 6; ++k) {
    const double ax = outline[k][0], ay = outline[k][1];
    const double bx = outline[(k + 1) % 6][0], by = outline[(k + 1) % 6][1];
    const double len2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
    const double t = std::clamp(((x - ax) * (bx - ax) + (y - ay) * (by - ay)) / len2, 0.0, 1.0);
    d = std::min(d, std::hypot(x - ax - t * (bx - ax), y - ay - t * (by - ay)));
  }
  const bool inside = (x > 0 && y > 0) && ((x < 20 && y < 10) || (x < 10 && y < 20));
  return inside ? d : -d;
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
