#pragma once
// Exact point-in-closed-mesh test by ray parity. OpenVDB's mesh voxelization decides the sign by
// flooding from outside, so an enclosed cavity (a hollow body) reads as solid; this test corrects it.
#include <array>
#include <vector>

#include "shard/geometry/stl.hpp"

namespace shard::geometry {

class InsideTest {
 public:
  explicit InsideTest(const TriangleMesh& mesh);
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
  std::array<AxisGrid, 3> grids_;
};

}  // namespace shard::geometry
