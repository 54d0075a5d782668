// STL reading, vertex welding and the closed-solid checks, each error asserted on its message.
#include <doctest/doctest.h>

#include <fstream>

#include "mesh_fixtures.hpp"
#include "shard/geometry/stl.hpp"

using namespace shard;
using namespace shard::geometry;

namespace {
std::string error_of(const TriangleMesh& mesh, const std::string& name = "body.stl") {
  try {
    require_closed_solid(mesh, name);
  } catch (const StlError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("binary and ASCII STL of the same cube give the same mesh") {
  const auto binary = read_stl(test::geometry_dir() + "/cube_10mm.stl", 0.001);
  const auto ascii = read_stl(test::geometry_dir() + "/cube_10mm_ascii.stl", 0.001);
  // 36 corners in the file weld to the cube's 8 vertices.
  CHECK(binary.vertices.size() == 8);
  CHECK(binary.faces.size() == 12);
  REQUIRE(ascii.vertices.size() == binary.vertices.size());
  REQUIRE(ascii.faces == binary.faces);
  for (std::size_t i = 0; i < ascii.vertices.size(); ++i) CHECK(ascii.vertices[i] == binary.vertices[i]);
  // Exactly 1e-6 m^3 up to the rounding of 0.001 * 10.
  CHECK(signed_volume(binary) == doctest::Approx(1e-6).epsilon(1e-12));
  const auto box = bounding_box(binary);
  CHECK(box.upper.x() == doctest::Approx(0.01).epsilon(1e-12));
  CHECK_NOTHROW(require_closed_solid(binary, "cube_10mm.stl"));
}

TEST_CASE("the scene bodies are closed, outward and free of crossings") {
  for (const char* name : {"beam_180x30x35.stl", "filter_cake_shard.stl", "sphere_r10mm.stl", "shell_r10_r6mm.stl"}) {
    CAPTURE(name);
    const auto mesh = read_stl(test::geometry_dir() + "/" + name, 0.001);
    CHECK_NOTHROW(require_closed_solid(mesh, name));
  }
  // Beam volume 180 x 30 x 35 mm^3 exactly; the shell is the outer minus the inner polyhedron.
  CHECK(signed_volume(read_stl(test::geometry_dir() + "/beam_180x30x35.stl", 0.001)) ==
        doctest::Approx(180e-3 * 30e-3 * 35e-3).epsilon(1e-9));
  const double outer = signed_volume(read_stl(test::geometry_dir() + "/sphere_r10mm.stl", 0.001));
  const double shell = signed_volume(read_stl(test::geometry_dir() + "/shell_r10_r6mm.stl", 0.001));
  CHECK(shell == doctest::Approx(outer * (1.0 - 0.216)).epsilon(1e-6));  // (6/10)^3 = 0.216
}

TEST_CASE("a missing file and an empty file are named in the error") {
  CHECK_THROWS_WITH_AS(read_stl("/nonexistent/part.stl"), doctest::Contains("'/nonexistent/part.stl' does not exist"),
                       StlError);
  const auto dir = test::scratch_dir("stl_empty");
  { std::ofstream(dir / "empty.stl"); }
  CHECK_THROWS_WITH_AS(read_stl(dir / "empty.stl"), doctest::Contains("is empty"), StlError);
  { std::ofstream(dir / "garbage.stl") << "this is not a mesh"; }
  CHECK_THROWS_WITH_AS(read_stl(dir / "garbage.stl"), doctest::Contains("neither ASCII STL"), StlError);
  { std::ofstream(dir / "nofacets.stl") << "solid nothing\nendsolid nothing\n"; }
  CHECK_THROWS_WITH_AS(read_stl(dir / "nofacets.stl"), doctest::Contains("contains no triangles"), StlError);
  CHECK_THROWS_WITH_AS(read_stl(test::geometry_dir() + "/cube_10mm.stl", 0.0), doctest::Contains("scale must be > 0"),
                       StlError);
}

TEST_CASE("a truncated binary STL is refused, not read half") {
  const auto dir = test::scratch_dir("stl_truncated");
  std::ifstream in(test::geometry_dir() + "/cube_10mm.stl", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "cut.stl", std::ios::binary) << bytes.substr(0, bytes.size() - 30);
  CHECK_THROWS_AS(read_stl(dir / "cut.stl"), StlError);
}

TEST_CASE("open, misoriented, inverted and self-intersecting meshes are refused with the fix") {
  const auto cube = test::box_mesh(Vec3::Zero(), Vec3::Constant(10.0));
  CHECK(error_of(cube).empty());

  auto open = cube;
  open.faces.pop_back();  // one missing triangle leaves its three edges open
  CHECK(inspect_mesh(open).open_edges == 3);
  CHECK(error_of(open).find("'body.stl' is not closed: 3 open edges") != std::string::npos);

  auto flipped_one = cube;
  std::swap(flipped_one.faces[0][1], flipped_one.faces[0][2]);
  CHECK(inspect_mesh(flipped_one).misoriented_edges == 3);
  CHECK(error_of(flipped_one).find("inconsistently oriented") != std::string::npos);

  auto inverted = cube;
  for (auto& f : inverted.faces) std::swap(f[1], f[2]);
  CHECK(signed_volume(inverted) == doctest::Approx(-1000.0));
  CHECK(error_of(inverted).find("inverted normals") != std::string::npos);

  // Two closed cubes overlapping without a boolean union: edges of one pierce faces of the other.
  const auto crossing = test::merged(cube, test::box_mesh(Vec3(3, 4, 5), Vec3(13, 14, 15)));
  CHECK(inspect_mesh(crossing).closed());
  CHECK(count_self_intersections(crossing, 1000) > 0);
  CHECK(error_of(crossing).find("self-intersecting") != std::string::npos);
  // Two separate cubes do not cross.
  CHECK(count_self_intersections(test::merged(cube, test::box_mesh(Vec3(20, 0, 0), Vec3(30, 10, 10))), 1000) == 0);
}
