// stl_fill on the test bodies: density, containment, no overlap, connectivity, isotropy,
// hollowness, determinism, and every bad-geometry error asserted on its message.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>

#include "mesh_fixtures.hpp"
#include "packing_checks.hpp"
#include "shard/geometry/advancing_front.hpp"
#include "shard/geometry/mesh_repair.hpp"
#include "shard/geometry/packing_quality.hpp"
#include "signed_distance_field.hpp"
#include "stl_fill.hpp"

using namespace shard;
using namespace shard::stl_fill;

namespace {

StlFillSettings settings(const std::string& file, double d_min, double d_max) {
  StlFillSettings s;
  s.file = file;
  s.scale = 0.001;
  s.diameter_min = d_min;
  s.diameter_max = d_max;
  return s;
}

GeneratorContext context_in(const std::string& dir, std::uint64_t seed = 3) {
  GeneratorContext c;
  c.scene_dir = dir;
  c.seed = seed;
  return c;
}

double quality(const GeneratedBody& body, const std::string& name) {
  for (const auto& [key, value] : body.quality)
    if (key == name) return value;
  FAIL("quality figure " << name << " missing");
  return 0.0;
}

// Exact signed distance to a convex polyhedron from inside: the largest signed plane distance.
double convex_distance(const geometry::TriangleMesh& mesh, const Vec3& p) {
  double d = -std::numeric_limits<double>::infinity();
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3 n = (mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a).normalized();
    d = std::max(d, n.dot(p - a));
  }
  return d;
}

std::string fill_error(const StlFillSettings& s, const std::string& dir) {
  try {
    StlFill(s).generate(context_in(dir));
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("the signed distance field matches the exact distance of a cube to within a voxel") {
  const auto cube = test::box_mesh(Vec3::Zero(), Vec3::Constant(0.01));
  const double voxel = 1e-4;
  const SignedDistanceField field(cube, voxel, 2e-3);
  for (const Vec3& p : {Vec3(0.005, 0.005, 0.0005), Vec3(0.001, 0.004, 0.006), Vec3(0.0099, 0.002, 0.005)})
    CHECK(std::abs(field.distance(p) - convex_distance(cube, p)) <= voxel);  // absolute: the test's own claim
  // Deep inside reads minus the band (stored as float32: relative rounding 1e-7).
  CHECK(field.distance(Vec3(0.005, 0.005, 0.005)) <= -2e-3 * (1 - 1e-6));
  CHECK(field.distance(Vec3(0.02, 0.005, 0.005)) > 0.0);      // far outside stays outside
}

TEST_CASE("a cube and a sphere filled: dense, inside, no overlap, one isotropic network") {
  struct Case {
    const char* file;
    double d_min, d_max;
  };
  for (const Case& c : {Case{"cube_10mm.stl", 0.3e-3, 0.4e-3}, Case{"sphere_r10mm.stl", 0.5e-3, 0.65e-3}}) {
    CAPTURE(c.file);
    const auto s = settings(c.file, c.d_min, c.d_max);
    const auto body = StlFill(s).generate(context_in(test::geometry_dir()));
    const auto mesh = geometry::read_stl(test::geometry_dir() + "/" + c.file, 0.001);
    const double voxel = c.d_min / 4.0;
    std::size_t outside = 0;
    for (std::size_t i = 0; i < body.position.size(); ++i)
      if (convex_distance(mesh, body.position[i]) > -body.radius[i] + voxel) ++outside;
    CHECK(outside == 0);
    MESSAGE(geometry::format_quality(body.quality));
    CHECK(quality(body, "solid_fraction") >= 0.55);
    CHECK(quality(body, "max_overlap") <= 1e-9);
    CHECK(quality(body, "bond_components") == 1.0);
    CHECK(quality(body, "fabric_deviator") <= 0.05);
    CHECK(quality(body, "hole_fraction") <= 0.001);
  }
}

TEST_CASE("a thick spherical shell is filled and stays hollow") {
  const auto body = StlFill(settings("shell_r10_r6mm.stl", 0.5e-3, 0.65e-3)).generate(context_in(test::geometry_dir()));
  const double voxel = 0.5e-3 / 4.0;
  double innermost = 1.0, outermost = 0.0;
  for (std::size_t i = 0; i < body.position.size(); ++i) {
    innermost = std::min(innermost, body.position[i].norm() - body.radius[i]);
    outermost = std::max(outermost, body.position[i].norm() + body.radius[i]);
  }
  // The inner polyhedron lies inside the 6 mm sphere: a sphere in the cavity would end below it.
  CHECK(innermost >= 6e-3 - voxel);
  CHECK(outermost <= 10e-3 + voxel);
  // ... and the front went all the way round the cavity.
  CHECK(quality(body, "hole_fraction") <= 0.001);
  CHECK(quality(body, "bond_components") == 1.0);
}

TEST_CASE("same seed, same packing bit for bit") {
  const auto s = settings("cube_10mm.stl", 0.6e-3, 0.8e-3);
  const auto a = StlFill(s).generate(context_in(test::geometry_dir(), 5));
  const auto b = StlFill(s).generate(context_in(test::geometry_dir(), 5));
  REQUIRE(a.position.size() == b.position.size());
  CHECK(std::memcmp(a.position.data(), b.position.data(), a.position.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(a.radius.data(), b.radius.data(), a.radius.size() * sizeof(double)) == 0);
  CHECK(a.bonds == b.bonds);
  const auto c = StlFill(s).generate(context_in(test::geometry_dir(), 6));
  CHECK((c.position.size() != a.position.size() ||
         std::memcmp(a.radius.data(), c.radius.data(), a.radius.size() * sizeof(double)) != 0));
}

TEST_CASE("bad geometry gives a clear error, never a hang or a half-filled body") {
  const auto dir = test::scratch_dir("stl_fill_errors");
  const Vec3 lo = Vec3::Zero(), hi = Vec3::Constant(10.0);
  auto write = [&](const std::string& name, const geometry::TriangleMesh& mesh) {
    geometry::write_stl(dir / name, mesh, geometry::StlFormat::Binary);
  };
  auto cube = test::box_mesh(lo, hi);
  auto open = cube;
  open.faces.pop_back();
  write("open.stl", open);
  auto inverted = cube;
  for (auto& f : inverted.faces) std::swap(f[1], f[2]);
  write("inverted.stl", inverted);
  write("crossing.stl", test::merged(cube, test::box_mesh(Vec3(3, 4, 5), Vec3(13, 14, 15))));
  write("thin.stl", test::box_mesh(lo, Vec3(10, 10, 0.8)));
  write("two_parts.stl", test::merged(cube, test::box_mesh(Vec3(20, 0, 0), Vec3(30, 10, 10))));
  // A plate 0.8 mm thick tilted by 45 degrees: its bounding box is wide, but no sphere of
  // diameter >= 0.9 mm fits inside.
  auto tilted = test::box_mesh(lo, Vec3(10, 10, 0.8));
  const Eigen::AngleAxisd tilt(0.25 * 3.14159265358979, Vec3::UnitX());
  for (Vec3& v : tilted.vertices) v = tilt * v;
  write("tilted_plate.stl", tilted);
  { std::ofstream(dir / "empty.stl"); }

  const std::string d = dir.string();
  CHECK(fill_error(settings("missing.stl", 0.5e-3, 1e-3), d).find("missing.stl' does not exist") != std::string::npos);
  CHECK(fill_error(settings("empty.stl", 0.5e-3, 1e-3), d).find("is empty") != std::string::npos);
  CHECK(fill_error(settings("open.stl", 0.5e-3, 1e-3), d).find("is not closed: 3 open edges") != std::string::npos);
  CHECK(fill_error(settings("inverted.stl", 0.5e-3, 1e-3), d).find("inverted normals") != std::string::npos);
  CHECK(fill_error(settings("crossing.stl", 0.5e-3, 1e-3), d).find("self-intersecting") != std::string::npos);
  CHECK(fill_error(settings("thin.stl", 0.5e-3, 1e-3), d).find("too thin") != std::string::npos);
  CHECK(fill_error(settings("tilted_plate.stl", 0.9e-3, 1e-3), d).find("too thin") != std::string::npos);
  const std::string partly = fill_error(settings("two_parts.stl", 0.8e-3, 1e-3), d);
  CHECK(partly.find("filled only partly") != std::string::npos);
  CHECK(partly.find("separate pieces") != std::string::npos);
}

// ---- bodies with the small defects of real files (mesh_repair.hpp) ----

namespace {

// Signed distance to the analytic torus around z (tube centre radius R, tube radius r).
double torus_distance(const Vec3& p, double R, double r) {
  return std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r;
}

// Lattice points (spacing h) that the field puts inside, and those classified unlike the analytic
// torus further than `band` from its surface.
struct TorusCount {
  std::size_t inside = 0;
  std::size_t wrong = 0;
};
TorusCount count_torus(const SignedDistanceField& field, double R, double r, double h, double band) {
  TorusCount c;
  for (double x = -R - r + 0.5 * h; x < R + r; x += h)
    for (double y = -R - r + 0.5 * h; y < R + r; y += h)
      for (double z = -r + 0.5 * h; z < r; z += h) {
        const Vec3 p(x, y, z);
        const bool inside = field.distance(p) < 0.0;
        c.inside += inside ? 1 : 0;
        const double exact = torus_distance(p, R, r);
        if (std::abs(exact) > band && inside != (exact < 0.0)) ++c.wrong;
      }
  return c;
}

}  // namespace

TEST_CASE("a torus with last-bit seams is welded, filled, and its field is the torus") {
  const auto dir = test::scratch_dir("stl_fill_torus");
  geometry::write_stl(dir / "torus.stl", test::seamed_torus(10.0, 4.0, 96, 48, true), geometry::StlFormat::Binary);
  // The same torus with exact seams: read_stl merges them by their bits, as welding should.
  geometry::write_stl(dir / "exact.stl", test::seamed_torus(10.0, 4.0, 96, 48, false), geometry::StlFormat::Binary);
  std::vector<std::string> log;
  auto context = context_in(dir.string());
  context.log = [&log](const std::string& line) { log.push_back(line); };
  const auto body = StlFill(settings("torus.stl", 0.7e-3, 0.9e-3)).generate(context);
  bool welded_logged = false;
  for (const auto& line : log) welded_logged = welded_logged || line.find("145 vertices welded") != std::string::npos;
  CHECK(welded_logged);
  MESSAGE(geometry::format_quality(body.quality));
  CHECK(quality(body, "hole_fraction") <= 0.001);
  CHECK(quality(body, "bond_components") == 1.0);
  std::size_t outside = 0;
  for (std::size_t i = 0; i < body.position.size(); ++i)
    if (torus_distance(body.position[i], 10e-3, 4e-3) > -body.radius[i] + 0.7e-3 / 4.0) ++outside;
  CHECK(outside == 0);
  // Welding keeps the first copy of each vertex, which is the vertex the exact seams merge into:
  // the two bodies are the same mesh, so the packings agree bit for bit.
  const auto exact = StlFill(settings("exact.stl", 0.7e-3, 0.9e-3)).generate(context_in(dir.string()));
  REQUIRE(exact.position.size() == body.position.size());
  CHECK(std::memcmp(exact.position.data(), body.position.data(), body.position.size() * sizeof(Vec3)) == 0);
  CHECK(exact.bonds == body.bonds);

  // The field of the welded mesh, on a lattice of spacing h = 0.25 mm (401,408 points). The
  // inscribed polyhedron lies within 0.01 mm of the torus (sagitta of the 48-gon: 4 mm x (1 -
  // cos(pi/48)) = 0.0086 mm), so every point further than 0.05 mm from the surface must be
  // classified as the torus says. The count of points inside estimates the volume to about
  // sqrt(points next to the surface) x h^3 = sqrt(1579 mm^2 / h^2) x h^3 = 2.5 mm^3 = 0.08 %;
  // the polyhedron is 0.35 % smaller than 2 pi^2 R r^2 (test_stl): 0.9965 +- 0.004 (5 sigma).
  auto mesh = geometry::read_stl(dir / "torus.stl", 0.001);
  geometry::repair_closed_solid(mesh, "torus.stl");
  const double h = 0.25e-3;
  const SignedDistanceField field(mesh, 0.5e-3 / 4.0, 0.5e-3);
  const TorusCount count = count_torus(field, 10e-3, 4e-3, h, 0.05e-3);
  CHECK(count.wrong == 0);
  const double analytic = 2.0 * std::numbers::pi * std::numbers::pi * 10e-3 * 4e-3 * 4e-3;
  CHECK(static_cast<double>(count.inside) * h * h * h / analytic == doctest::Approx(0.9965).epsilon(0.004));
}

TEST_CASE("a torus with a 1 um seam crack is signed by the winding number like the closed one") {
  // Shift 1e-3 mm: above the weld tolerance (4.0e-5 mm), below the gap tolerance (0.040 mm).
  auto cracked = test::seamed_torus(10.0, 4.0, 96, 48, false, 1e-3);
  for (Vec3& v : cracked.vertices) v *= 0.001;
  const geometry::SolidRepair repair = geometry::repair_closed_solid(cracked, "cracked.stl");
  REQUIRE(repair.edges.gap_edges > 0);
  const SignedDistanceField field(cracked, 0.5e-3 / 4.0, 0.5e-3, geometry::SignRule::WindingWhenRaysDisagree);
  // As for the welded torus; the crack adds 1 um to the band.
  const TorusCount count = count_torus(field, 10e-3, 4e-3, 0.25e-3, 0.05e-3);
  CHECK(count.wrong == 0);
}

TEST_CASE("an L-prism with T-junction caps fills like the same prism triangulated conformingly") {
  const auto dir = test::scratch_dir("stl_fill_l_prism");
  geometry::write_stl(dir / "l_t.stl", test::l_prism(true), geometry::StlFormat::Binary);
  geometry::write_stl(dir / "l_conforming.stl", test::l_prism(false), geometry::StlFormat::Binary);
  std::vector<std::string> log;
  auto context = context_in(dir.string());
  context.log = [&log](const std::string& line) { log.push_back(line); };
  const auto t_body = StlFill(settings("l_t.stl", 0.7e-3, 0.9e-3)).generate(context);
  const auto c_body = StlFill(settings("l_conforming.stl", 0.7e-3, 0.9e-3)).generate(context_in(dir.string()));
  bool t_logged = false;
  for (const auto& line : log) t_logged = t_logged || line.find("4 T-junction vertices") != std::string::npos;
  CHECK(t_logged);
  MESSAGE(geometry::format_quality(t_body.quality));
  MESSAGE(geometry::format_quality(c_body.quality));
  std::size_t outside = 0;
  for (std::size_t i = 0; i < t_body.position.size(); ++i) {
    const Vec3 p = t_body.position[i] * 1e3;  // mm
    const double depth = std::min({test::l_outline_inside_distance(p.x(), p.y()), p.z(), 10.0 - p.z()});
    if (depth < t_body.radius[i] * 1e3 - 0.7 / 4.0) ++outside;
  }
  CHECK(outside == 0);
  CHECK(quality(t_body, "hole_fraction") <= 0.001);
  CHECK(quality(t_body, "bond_components") == 1.0);
  // Both meshes bound the same solid, and the field's sign and distance do not depend on how the
  // surface is cut into triangles (the unsigned distance is to the same surface, up to float32
  // rounding): the fronts place the same spheres up to rounding-driven divergence, so the counts
  // differ by far less than 1 %.
  CHECK(static_cast<double>(t_body.position.size()) ==
        doctest::Approx(static_cast<double>(c_body.position.size())).epsilon(0.01));
  CHECK(quality(t_body, "solid_fraction") == doctest::Approx(quality(c_body, "solid_fraction")).epsilon(0.01).scale(0));
}

TEST_CASE("a box with one face missing is refused by stl_fill") {
  const auto dir = test::scratch_dir("stl_fill_lidless");
  auto lidless = test::box_mesh(Vec3::Zero(), Vec3::Constant(10.0));
  lidless.faces.resize(10);
  geometry::write_stl(dir / "lidless.stl", lidless, geometry::StlFormat::Binary);
  CHECK(fill_error(settings("lidless.stl", 0.5e-3, 1e-3), dir.string())
            .find("lidless.stl' is not closed: 4 open edges (holes in the surface") != std::string::npos);
}

TEST_CASE("conform_surface: every face of a cube ends in a layer of spheres that touch it") {
  auto s = settings("cube_10mm.stl", 0.6e-3, 0.8e-3);
  const auto mesh = geometry::read_stl(test::geometry_dir() + "/cube_10mm.stl", 0.001);
  const geometry::Box box = geometry::bounding_box(mesh);
  // A sphere touches a face when it is placed against it: within the placement's allowance of
  // 1e-3 of its radius.
  const double touching = 1e-3 * 0.3e-3;
  const auto rough = StlFill(s).generate(context_in(test::geometry_dir()));
  s.conform_surface = true;
  const auto flat = StlFill(s).generate(context_in(test::geometry_dir()));
  const auto rough_cover = test::touching_area_fraction(rough, box, touching);
  const auto flat_cover = test::touching_area_fraction(flat, box, touching);
  for (int face = 0; face < 6; ++face) {
    CAPTURE(face);
    // Without the option a sphere touches a face only by chance. With it, a fixture bearing
    // anywhere on a face meets a touching sphere within about two diameters: at least a fifth
    // of each face lies under the discs of spheres that touch it.
    CHECK(rough_cover[face] < 0.01);
    CHECK(flat_cover[face] > 0.2);
  }
  std::size_t outside = 0;
  for (std::size_t i = 0; i < flat.position.size(); ++i)
    if (convex_distance(mesh, flat.position[i]) > -flat.radius[i] + touching) ++outside;
  CHECK(outside == 0);
  // The layer against the faces costs the packing nothing it is judged by.
  CHECK(quality(flat, "solid_fraction") >= quality(rough, "solid_fraction") - 0.01);
  CHECK(quality(flat, "max_overlap") <= 1e-9);
  CHECK(quality(flat, "bond_components") == 1.0);
  CHECK(quality(flat, "fabric_deviator") <= 0.05);
  CHECK(quality(flat, "hole_fraction") <= 0.001);
}

namespace {

// Share of the faceted sphere's surface under the discs of the spheres that touch it (gap within
// `tolerance`); also the count of spheres that cross it by more than `tolerance`.
std::pair<double, std::size_t> touching_share(const GeneratedBody& body, const geometry::TriangleMesh& mesh,
                                              double tolerance) {
  double surface = 0.0;
  for (const auto& f : mesh.faces)
    surface += 0.5 * (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]).norm();
  double covered = 0.0;
  std::size_t crossing = 0;
  for (std::size_t i = 0; i < body.position.size(); ++i) {
    const double gap = -convex_distance(mesh, body.position[i]) - body.radius[i];
    if (gap < -tolerance) ++crossing;
    if (std::abs(gap) <= tolerance) covered += std::numbers::pi * body.radius[i] * body.radius[i];
  }
  return {covered / surface, crossing};
}

}  // namespace

TEST_CASE("conform_surface on a curved body: the outer spheres touch the faceted sphere from inside") {
  auto s = settings("sphere_r10mm.stl", 0.5e-3, 0.65e-3);
  const auto rough = StlFill(s).generate(context_in(test::geometry_dir()));
  s.conform_surface = true;
  const auto flat = StlFill(s).generate(context_in(test::geometry_dir()));
  const auto mesh = geometry::read_stl(test::geometry_dir() + "/sphere_r10mm.stl", 0.001);
  // Along the facets' edges the voxelized distance is not planar, so a sphere placed there may
  // cross the surface by up to a voxel, as the plain fill may (the cube-and-sphere case above).
  const double voxel = 0.5e-3 / 4.0;
  const double rough_share = touching_share(rough, mesh, 0.01 * 0.25e-3).first;
  const double flat_share = touching_share(flat, mesh, 0.01 * 0.25e-3).first;
  CHECK(touching_share(flat, mesh, voxel).second == 0);
  // Spheres touch a convex surface from inside further apart than a plane (the surface curves
  // away between them): a tenth of it under touching discs, against none by chance.
  CHECK(rough_share < 0.01);
  CHECK(flat_share > 0.1);
  CHECK(quality(flat, "max_overlap") <= 1e-9);
  CHECK(quality(flat, "bond_components") == 1.0);
  CHECK(quality(flat, "hole_fraction") <= 0.001);
}
