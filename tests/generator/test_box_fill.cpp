// box_fill: lattice geometry, the seeded advancing-front packing and its determinism.
#include <doctest/doctest.h>

#include <cstring>
#include <map>

#include "box_fill.hpp"
#include "packing_checks.hpp"
#include "shard/geometry/packing_quality.hpp"

using namespace shard;
using namespace shard::box_fill;

namespace {

BoxFillSettings settings(Lattice lattice, double d_min, double d_max, double gap, double edge) {
  BoxFillSettings s;
  s.min_corner = Vec3::Zero();
  s.max_corner = Vec3::Constant(edge);
  s.lattice = lattice;
  s.diameter_min = d_min;
  s.diameter_max = d_max;
  s.gap = gap;
  return s;
}

double quality(const GeneratedBody& body, const std::string& name) {
  for (const auto& [key, value] : body.quality)
    if (key == name) return value;
  FAIL("quality figure " << name << " missing");
  return 0.0;
}

// Bonds per sphere, for spheres at least 2 d away from every face (no wall effect).
std::vector<int> interior_coordination(const GeneratedBody& body, double edge, double d) {
  std::vector<int> count(body.position.size(), 0);
  for (const auto& [i, j] : body.bonds) ++count[i], ++count[j];
  std::vector<int> interior;
  for (std::size_t i = 0; i < count.size(); ++i)
    if ((body.position[i].array() > 2 * d).all() && (body.position[i].array() < edge - 2 * d).all())
      interior.push_back(count[i]);
  return interior;
}

}  // namespace

TEST_CASE("lattices: every sphere in the box, interior coordination 6 (cubic) and 12 (fcc, hcp)") {
  const double d = 1e-3, edge = 8e-3;
  GeneratorContext context;
  // gap 0.01 x r bonds touching spheres only: second neighbours are >= sqrt(2) d - d = 0.41 d apart.
  for (auto [lattice, expected] : {std::pair{Lattice::Cubic, 6}, {Lattice::Fcc, 12}, {Lattice::Hcp, 12}}) {
    CAPTURE(static_cast<int>(lattice));
    const auto body = BoxFill(settings(lattice, d, d, 0.01, edge)).generate(context);
    REQUIRE(body.position.size() > 100);
    for (std::size_t i = 0; i < body.position.size(); ++i) {
      CHECK((body.position[i].array() >= body.radius[i] - 1e-15).all());
      CHECK((body.position[i].array() <= edge - body.radius[i] + 1e-15).all());
    }
    const auto interior = interior_coordination(body, edge, d);
    REQUIRE(!interior.empty());
    for (int c : interior) CHECK(c == expected);
    CHECK(quality(body, "max_overlap") <= 1e-9);
  }
  // Cubic and fcc bonds are isotropic as a second-order fabric (cubic symmetry): deviator ~ 0 up to
  // the boundary; 8 x 8 x 8 cubic sites give exactly 0 by symmetry.
  CHECK(quality(BoxFill(settings(Lattice::Cubic, d, d, 0.01, edge)).generate(context), "fabric_deviator") < 1e-12);
  // fcc packs 0.7405 in bulk; a box of 8 d loses the boundary layer.
  CHECK(quality(BoxFill(settings(Lattice::Fcc, d, d, 0.01, 20 * d)).generate(context), "solid_fraction") > 0.6);
}

TEST_CASE("random packing: dense, inside, no overlap, one isotropic bond network") {
  const double edge = 24e-3;
  GeneratorContext context;
  context.seed = 7;
  const auto body = BoxFill(settings(Lattice::Random, 0.7e-3, 1.0e-3, 0.7, edge)).generate(context);
  INFO(body.quality.size());
  for (std::size_t i = 0; i < body.position.size(); ++i) {
    CHECK((body.position[i].array() >= body.radius[i] * (1 - 1e-12)).all());
    CHECK((body.position[i].array() <= edge - body.radius[i] * (1 - 1e-12)).all());
  }
  // Wall layer included: the bulk of an advancing-front packing is ~0.58.
  CHECK(quality(body, "solid_fraction") >= 0.52);
  CHECK(quality(body, "max_overlap") <= 1e-9);
  CHECK(quality(body, "bond_components") == 1.0);
  CHECK(quality(body, "fabric_deviator") <= 0.05);
  CHECK(quality(body, "psd_ks_distance") <= 0.05);
  CHECK(quality(body, "hole_fraction") == 0.0);
}

TEST_CASE("same seed, same packing bit for bit; another seed, another packing") {
  GeneratorContext context;
  context.seed = 11;
  const auto s = settings(Lattice::Random, 0.7e-3, 1.0e-3, 0.7, 10e-3);
  const auto a = BoxFill(s).generate(context);
  const auto b = BoxFill(s).generate(context);
  REQUIRE(a.position.size() == b.position.size());
  CHECK(std::memcmp(a.position.data(), b.position.data(), a.position.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(a.radius.data(), b.radius.data(), a.radius.size() * sizeof(double)) == 0);
  CHECK(a.bonds == b.bonds);
  auto shifted = s;
  shifted.seed_offset = 1;
  const auto c = BoxFill(shifted).generate(context);
  CHECK((c.position.size() != a.position.size() ||
         std::memcmp(a.radius.data(), c.radius.data(), a.radius.size() * sizeof(double)) != 0));
}

TEST_CASE("random packing with conform_surface: each face borne by a layer of touching spheres") {
  const double edge = 12e-3;
  GeneratorContext context;
  context.seed = 7;
  auto s = settings(Lattice::Random, 0.7e-3, 1.0e-3, 0.7, edge);
  s.conform_surface = true;
  const auto body = BoxFill(s).generate(context);
  const geometry::Box box{Vec3::Zero(), Vec3::Constant(edge)};
  // The box's distance is exact, so a sphere placed against a face touches it to rounding; 1e-3 r
  // is the placement's allowance.
  const auto cover = test::touching_area_fraction(body, box, 1e-3 * 0.35e-3);
  for (int face = 0; face < 6; ++face) {
    CAPTURE(face);
    CHECK(cover[face] > 0.2);
  }
  for (std::size_t i = 0; i < body.position.size(); ++i) {
    CHECK((body.position[i].array() >= body.radius[i] * (1 - 1e-3)).all());
    CHECK((body.position[i].array() <= edge - body.radius[i] * (1 - 1e-3)).all());
  }
  CHECK(quality(body, "max_overlap") <= 1e-9);
  CHECK(quality(body, "bond_components") == 1.0);
  CHECK(quality(body, "hole_fraction") == 0.0);
}

TEST_CASE("bad box parameters are refused with the reason") {
  CHECK_THROWS_WITH(BoxFill(settings(Lattice::Random, 1e-3, 2e-3, 0.7, 1.5e-3)), doctest::Contains("at least diameter_max"));
  CHECK_THROWS_WITH(BoxFill(settings(Lattice::Random, 2e-3, 1e-3, 0.7, 1e-2)), doctest::Contains("diameter_min <= diameter_max"));
  auto lattice_conformed = settings(Lattice::Hcp, 1e-3, 1e-3, 0.7, 1e-2);
  lattice_conformed.conform_surface = true;
  CHECK_THROWS_WITH(BoxFill{lattice_conformed}, doctest::Contains("conform_surface = true applies to lattice = \"random\""));
  CHECK_THROWS_WITH(parse_lattice("bcc"), doctest::Contains("\"fcc\", \"hcp\", \"cubic\" or \"random\""));
}
