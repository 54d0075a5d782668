#pragma once
// Triangulated surfaces from STL files: the parent-body geometry of the STL filling (seed sec. III)
// and the kernel's mesh walls.
#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/types.hpp"

namespace shard::geometry {

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<Index, 3>> faces;  // counter-clockwise seen from outside
};

// Every problem with an STL file or its mesh: the message names the file, what is wrong and
// what to do about it.
class StlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads a binary or ASCII STL (detected by content, not by extension), multiplies coordinates by
// `scale` (an STL in mm with scale 0.001 gives metres) and merges vertices with identical float32
// coordinates, which is how STL writers repeat a shared corner (corners that differ in the last
// bits are welded within a tolerance by weld_vertices(), mesh_repair.hpp). Faces that collapse to a line
// after merging are dropped. Throws StlError on a missing, unreadable, truncated or empty file.
// Open surfaces are accepted here (walls may be open); require_closed_solid() checks bodies.
TriangleMesh read_stl(const std::filesystem::path& file, double scale = 1.0);

enum class StlFormat { Binary, Ascii };
// Writes float32 coordinates in both formats, so read_stl of either gives the same mesh.
void write_stl(const std::filesystem::path& file, const TriangleMesh& mesh, StlFormat format,
               const std::string& name = "shard");

struct MeshReport {
  std::size_t open_edges = 0;         // edges used by one face only (holes in the surface)
  std::size_t nonmanifold_edges = 0;  // edges used by more than two faces
  std::size_t misoriented_edges = 0;  // edges whose two faces traverse it in the same direction
  double signed_volume = 0.0;         // > 0: normals point outward
  bool closed() const { return open_edges == 0 && nonmanifold_edges == 0; }
  bool consistently_oriented() const { return misoriented_edges == 0; }
};

MeshReport inspect_mesh(const TriangleMesh& mesh);

// Signed volume by the divergence theorem; positive when face normals point outward.
double signed_volume(const TriangleMesh& mesh);

// Pairs of faces that cross each other. Faces sharing a vertex are not tested (they touch by
// construction), and coplanar overlaps are not detected: the test is that an edge of one face
// pierces the interior of the other, the common case of two bodies merged without a boolean union.
// Uses a uniform grid over face bounding boxes, so it runs in about O(faces).
std::size_t count_self_intersections(const TriangleMesh& mesh, std::size_t stop_after = 1);

// The checks a body to be filled must pass: non-empty, closed (watertight; T-junctions and cracks
// narrower than the default gap tolerance count as closed: mesh_repair.hpp), consistently
// oriented, outward normals (positive volume), not self-intersecting. Throws StlError naming
// `file` and the fix. It does not weld: repair_closed_solid() (mesh_repair.hpp) welds, then checks.
void require_closed_solid(const TriangleMesh& mesh, const std::filesystem::path& file);

// Axis-aligned bounds of the vertices.
struct Box {
  Vec3 lower;
  Vec3 upper;
};
Box bounding_box(const TriangleMesh& mesh);

}  // namespace shard::geometry
