// stl_fill on the test bodies: density, containment, no overlap, connectivity, isotropy,
// hollowness, determinism, and every bad-geometry error asserted on its message.
#include <doctest/doctest.h>

#include <cstring>
#include <fstream>

#include "mesh_fixtures.hpp"
#include "shard/geometry/advancing_front.hpp"
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
    CHECK(field.distance(p) == doctest::Approx(convex_distance(cube, p)).epsilon(0).scale(1).epsilon(voxel / 1e-3));
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
