#pragma once
// Exact point-in-closed-mesh test by ray parity. OpenVDB's mesh voxelization decides the sign by
// flooding from outside, so an enclosed cavity (a hollow body) reads as solid; this test corrects it.
// For a surface closed only geometrically (T-junctions) or up to small cracks, the generalised
// winding number decides wherever the three rays disagree.
#include <array>
#include <vector>

#include "shard/geometry/stl.hpp"

namespace shard::geometry {

// Generalised winding number of the surface around `point` (Jacobson, Kavan and Sorkine-Hornung
// 2013): the signed solid angles of the faces (Van Oosterom and Strackee 1983) summed and divided
// by 4 pi. 1 inside and 0 outside a closed outward surface; T-junctions do not change it, and a crack
// of width w changes it by about (its area) / (4 pi distance^2), i.e. only next to the crack.
// O(faces) per point.
double winding_number(const TriangleMesh& mesh, const Vec3& point);

enum class SignRule {
  RayMajority,              // a closed mesh: the majority of the three rays
  WindingWhenRaysDisagree,  // T-junctions or cracks: rays that disagree are settled by the winding number
};

class InsideTest {
 public:
  explicit InsideTest(const TriangleMesh& mesh, SignRule rule = SignRule::RayMajority);
  // Majority of three axis-aligned rays (+x, +y, +z), each counting face crossings in a 2D bucket
  // grid: a ray grazing an edge or vertex can miscount, two of three such rays practically never.
  bool inside(const Vec3& point) const;

 private:
  struct AxisGrid {
    int axis = 0;       // ray direction
    int u = 1, v = 2;   // projected coordinates
    double lo_u = 0, lo_v = 0, cell_u = 1, cell_v = 1;
    int n = 1;
    std::vector<int> start;  // CSR: faces of bucket b are faces[start[b] .. start[b+1])
    std::vector<Index> faces;
  };
  bool odd_crossings(const AxisGrid& grid, const Vec3& p) const;
  const TriangleMesh& mesh_;
  SignRule rule_;
  std::array<AxisGrid, 3> grids_;
};

}  // namespace shard::geometry
