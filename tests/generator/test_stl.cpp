// STL reading, vertex welding and the closed-solid checks, each error asserted on its message.
#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <numbers>

#include "mesh_fixtures.hpp"
#include "shard/geometry/inside_test.hpp"
#include "shard/geometry/mesh_repair.hpp"
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
  CHECK(signed_volume(binary) == doctest::Approx(1e-6).epsilon(1e-12).scale(0));
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
        doctest::Approx(180e-3 * 30e-3 * 35e-3).epsilon(1e-9).scale(0));
  const double outer = signed_volume(read_stl(test::geometry_dir() + "/sphere_r10mm.stl", 0.001));
  const double shell = signed_volume(read_stl(test::geometry_dir() + "/shell_r10_r6mm.stl", 0.001));
  CHECK(shell == doctest::Approx(outer * (1.0 - 0.216)).epsilon(1e-6).scale(0));  // (6/10)^3 = 0.216
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

// ---- small defects of real files: welding, T-junctions, cracks (mesh_repair.hpp) ----

TEST_CASE("a torus whose seam vertices differ in the last bits is welded shut") {
  // 96 x 48 segments: the seams hold 96 + 48 + 1 = 145 duplicate vertices and border 2 x (96 + 48)
  // = 288 open edges, the count the exact-bits reader reported for such a file.
  const auto dir = test::scratch_dir("stl_torus");
  write_stl(dir / "torus.stl", test::seamed_torus(10.0, 4.0, 96, 48, true), StlFormat::Binary);
  auto mesh = read_stl(dir / "torus.stl", 0.001);
  CHECK(mesh.vertices.size() == 97 * 49);
  CHECK(inspect_mesh(mesh).open_edges == 288);
  const double tolerance = default_weld_tolerance(mesh);
  // 1e-6 of the 40.4 mm diagonal: 4.0e-8 m, 14 times the up to 3 float32 ulps (3 x 9.5e-10 m at
  // 14 mm) that separate the seams, and 1/10^4 of the 0.39 mm shortest edge.
  CHECK(tolerance == doctest::Approx(1e-6 * std::sqrt(2 * 28e-3 * 28e-3 + 8e-3 * 8e-3)).epsilon(1e-6).scale(0));
  const SolidRepair repair = repair_closed_solid(mesh, "torus.stl");
  CHECK(repair.weld.vertices_welded == 145);
  CHECK(repair.weld.faces_dropped == 0);
  CHECK(repair.edges.open_edges == 0);
  CHECK(mesh.vertices.size() == 96 * 48);
  CHECK(inspect_mesh(mesh).closed());
  CHECK(repair.summary().find("145 vertices welded") != std::string::npos);
  // The polyhedron inscribed in the torus: its cross-section 48-gon has sin(2 pi/48)/(2 pi/48) =
  // 0.9971 of the circle's area and the 96-gon path 0.9993 of the circle's length, so its volume
  // lies 0.2-0.5 % below 2 pi^2 R r^2.
  const double analytic = 2.0 * std::numbers::pi * std::numbers::pi * 10e-3 * 4e-3 * 4e-3;
  CHECK(signed_volume(mesh) / analytic == doctest::Approx(0.9965).epsilon(0.0015));
}

TEST_CASE("an L-prism whose caps meet the walls at T-junctions is geometrically closed") {
  auto prism = test::l_prism(true);
  CHECK(inspect_mesh(prism).open_edges == 12);  // what the issue reported
  CHECK(signed_volume(prism) == doctest::Approx(3000.0).epsilon(1e-12));  // 300 mm^2 x 10 mm
  CHECK(inspect_mesh(test::l_prism(false)).closed());  // the same solid, conforming
  const OpenEdgeReport edges = classify_open_edges(prism, 1e-9, 1e-3);
  CHECK(edges.open_edges == 12);
  CHECK(edges.t_junctions == 4);  // (10,0) and (0,10) on both caps
  CHECK(edges.covered_edges == 12);
  CHECK(edges.geometrically_closed());
  const SolidRepair repair = repair_closed_solid(prism, "l_prism.stl");
  CHECK(repair.weld.vertices_welded == 0);
  CHECK(repair.edges.t_junctions == 4);
  CHECK(repair.summary().find("12 covered by 4 T-junction vertices (geometrically closed)") != std::string::npos);
  // The winding number ignores the T-junctions: 1 inside (also 1 um from the T-junction seam at
  // (10, 0, 0)), 0 outside. Each face's solid angle carries a rounding of ~1e-16 x (size / distance)
  // = 1e-16 x 1e4 at 1 um from a 20 mm face: 1e-9 bounds the 24 of them.
  for (const Vec3& p : {Vec3(5, 5, 5), Vec3(15, 5, 5), Vec3(5, 15, 5), Vec3(10, 1e-3, 1e-3), Vec3(1e-3, 10, 9.999)})
    CHECK(winding_number(prism, p) == doctest::Approx(1.0).epsilon(1e-9));
  for (const Vec3& p : {Vec3(15, 15, 5), Vec3(-1, 5, 5), Vec3(10, -1e-3, 1e-3), Vec3(-1e-3, 10, 10.001)})
    CHECK(std::abs(winding_number(prism, p)) < 1e-9);
}

TEST_CASE("cracks narrower than the gap tolerance are accepted, wider ones and missing faces refused") {
  // Seam shifted by 1 um (units: mm): 25 times the weld tolerance 1e-6 x 40.4 mm (not welded, not a
  // T-junction), 1/40 of the default gap tolerance 1e-3 x 40.4 mm.
  auto cracked = test::seamed_torus(10.0, 4.0, 96, 48, false, 1e-3);
  const SolidRepair repair = repair_closed_solid(cracked, "cracked.stl");
  CHECK(repair.weld.vertices_welded == 2);  // the three shifted copies of the seams' corner coincide
  CHECK(repair.edges.open_edges == 288);
  // Where a seam edge runs along x the shift slides it along itself: those pieces still lie on
  // each other (covered); the others border the crack.
  CHECK(repair.edges.gap_edges > 0);
  CHECK(repair.edges.covered_edges + repair.edges.gap_edges == 288);
  // The crack is the shift, 1 um, measured across: an edge normal to x (the u-seam at the outer
  // equator) sees all of it, none sees more.
  CHECK(repair.edges.largest_gap <= 1e-3 * (1 + 1e-6));
  CHECK(repair.edges.largest_gap >= 0.5e-3);
  CHECK(repair.edges.volume_ambiguity < kMaxVolumeAmbiguity);
  CHECK(repair.summary().find("warning: largest gap") != std::string::npos);
  // The same crack with a 0.5 um gap tolerance is refused.
  auto strict = test::seamed_torus(10.0, 4.0, 96, 48, false, 1e-3);
  CHECK_THROWS_WITH_AS(repair_closed_solid(strict, "cracked.stl", SolidTolerances{0.0, 0.5e-3}),
                       doctest::Contains("'cracked.stl' is not closed: 288 open edges"), StlError);

  // A weld tolerance as large as the body's edges would collapse it: refused, naming the key.
  auto cube = test::box_mesh(Vec3::Zero(), Vec3::Constant(10.0));
  CHECK_THROWS_WITH_AS(repair_closed_solid(cube, "cube.stl", SolidTolerances{20.0, 0.0}),
                       doctest::Contains("collapsed 12 of its 12 faces"), StlError);

  // A box with one face (two triangles) missing: a 10 x 10 hole.
  auto lidless = test::box_mesh(Vec3::Zero(), Vec3::Constant(10.0));
  lidless.faces.resize(10);
  CHECK_THROWS_WITH_AS(repair_closed_solid(lidless, "lidless.stl"),
                       doctest::Contains("'lidless.stl' is not closed: 4 open edges (holes in the surface; 4 of "
                                         "them border openings wider than the gap tolerance"),
                       StlError);
}

TEST_CASE("a clean mesh passes the repair unchanged, bit for bit") {
  for (const char* name : {"beam_180x30x35.stl", "filter_cake_shard.stl", "sphere_r10mm.stl", "shell_r10_r6mm.stl"}) {
    CAPTURE(name);
    const auto read = read_stl(test::geometry_dir() + "/" + name, 0.001);
    auto repaired = read;
    const SolidRepair repair = repair_closed_solid(repaired, name);
    CHECK(repair.untouched());
    CHECK(repaired.faces == read.faces);
    REQUIRE(repaired.vertices.size() == read.vertices.size());
    CHECK(std::memcmp(repaired.vertices.data(), read.vertices.data(), read.vertices.size() * sizeof(Vec3)) == 0);
  }
}

namespace {
// Cube [0,10]^3 whose +x and +y faces are each cut by a vertical slit `width` wide in their middle
// (y = 5 and x = 5): two cracks 10 long, open to the rays of a point on the cube's axis.
TriangleMesh slit_cube(double width) {
  TriangleMesh m = test::box_mesh(Vec3::Zero(), Vec3::Constant(10.0));
  m.faces.erase(m.faces.begin() + 10, m.faces.begin() + 12);  // +x quad
  m.faces.erase(m.faces.begin() + 6, m.faces.begin() + 8);    // +y quad
  auto vertex = [&](const Vec3& p) {
    for (std::size_t k = 0; k < m.vertices.size(); ++k)
      if (m.vertices[k] == p) return static_cast<Index>(k);
    m.vertices.push_back(p);
    return static_cast<Index>(m.vertices.size() - 1);
  };
  auto rectangle = [&](const Vec3& c, const Vec3& e1, const Vec3& e2) {  // outward normal e1 x e2
    const Index a = vertex(c), b = vertex(c + e1), d = vertex(c + e1 + e2), e = vertex(c + e2);
    m.faces.push_back({a, b, d});
    m.faces.push_back({a, d, e});
  };
  const double half = 5.0 - 0.5 * width;
  rectangle(Vec3(10, 0, 0), Vec3(0, half, 0), Vec3(0, 0, 10));
  rectangle(Vec3(10, 10 - half, 0), Vec3(0, half, 0), Vec3(0, 0, 10));
  rectangle(Vec3(0, 10, 0), Vec3(0, 0, 10), Vec3(half, 0, 0));
  rectangle(Vec3(10 - half, 10, 0), Vec3(0, 0, 10), Vec3(half, 0, 0));
  return m;
}
}  // namespace

TEST_CASE("where two rays pass through cracks, the winding number decides") {
  TriangleMesh cube = slit_cube(0.01);
  // Slits 0.01 wide: below the default gap tolerance 1e-3 x 17.3; their area 2 x 0.1 leaves
  // |0.1 (1,0,0) + 0.1 (0,1,0)| x 17.3 / (3 x 1000) = 0.08 % of the volume undecided (< 0.1 %).
  const SolidRepair repair = repair_closed_solid(cube, "slit_cube.stl");
  CHECK(repair.edges.largest_gap == doctest::Approx(0.01).epsilon(1e-9));
  // (The divergence-theorem volume misses the slits' flux, 2 x 10 x 0.1 / 3, measured from the origin.)
  CHECK(repair.edges.volume_ambiguity ==
        doctest::Approx(0.1 * std::sqrt(2.0) * std::sqrt(300.0) / (3.0 * (1000.0 - 2.0 / 3.0))).epsilon(1e-9).scale(0));
  // From the centre the +x and +y rays leave through the slits: one crossing of three, so the ray
  // majority calls the centre outside. Seen from there each slit (0.01 x 10 at distance 5)
  // subtends ~0.003 sr, so the winding number is 1 - 2 x 0.003 / (4 pi) = 0.9995: inside.
  const Vec3 centre(5, 5, 5);
  CHECK_FALSE(InsideTest(cube, SignRule::RayMajority).inside(centre));
  CHECK(InsideTest(cube, SignRule::WindingWhenRaysDisagree).inside(centre));
  CHECK(winding_number(cube, centre) == doctest::Approx(0.9995).epsilon(3e-4));
  // Outside, the rule changes nothing: a point on the slits' line beyond the cube.
  CHECK_FALSE(InsideTest(cube, SignRule::WindingWhenRaysDisagree).inside(Vec3(-1, 5, 5)));
  CHECK_FALSE(InsideTest(cube, SignRule::WindingWhenRaysDisagree).inside(Vec3(5, 5, 11)));
}
