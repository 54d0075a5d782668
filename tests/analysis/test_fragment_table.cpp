// Per-fragment quantities on hand-computed examples.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "shard/analysis/fragment_table.hpp"

using namespace shard;
using namespace shard::analysis;

namespace {
constexpr double kTol = 1e-12;  // all values are a few exact operations on O(1) numbers
}

TEST_CASE("fragment table: mass, volume, centre, velocity, d_eq, bounding box, body") {
  // Rows: a bonded pair (rows 0 and 2) and an isolated sphere (row 1).
  const std::vector<Index> id{10, 11, 12};
  const std::vector<Vec3> position{{0, 0, 0}, {5, 5, 5}, {2, 0, 0}};
  const std::vector<Vec3> velocity{{1, 0, 0}, {0, 0, -2}, {0, 1, 0}};
  const std::vector<double> radius{1.0, 0.5, 1.0};
  const std::vector<double> mass{1.0, 0.25, 3.0};
  const std::vector<std::int32_t> body{4, 2, 4};
  const std::vector<Index> bond_i{2}, bond_j{0};
  const ParticleSample sample{id, position, velocity, radius, mass, body};
  const FragmentAnalysis result = analyse_fragments(sample, {bond_i, bond_j});

  REQUIRE(result.fragments.size() == 2);
  CHECK(result.labels == std::vector<Index>{0, 1, 0});
  const Fragment& pair = result.fragments[0];
  CHECK(pair.particles == 2);
  CHECK(pair.mass == doctest::Approx(4.0).epsilon(kTol));
  const double unit_sphere = 4.0 / 3.0 * std::numbers::pi;
  CHECK(pair.volume == doctest::Approx(2 * unit_sphere).epsilon(kTol));
  // centre = (1*0 + 3*2)/4; velocity = (1*(1,0,0) + 3*(0,1,0))/4
  CHECK(pair.centre.x() == doctest::Approx(1.5).epsilon(kTol));
  CHECK(pair.centre.y() == doctest::Approx(0.0).epsilon(kTol));
  CHECK(pair.velocity.x() == doctest::Approx(0.25).epsilon(kTol));
  CHECK(pair.velocity.y() == doctest::Approx(0.75).epsilon(kTol));
  // Volume of two unit spheres = one sphere of radius 2^(1/3): d_eq = 2 * 2^(1/3).
  CHECK(pair.d_eq == doctest::Approx(2.0 * std::cbrt(2.0)).epsilon(kTol));
  CHECK(pair.box_min.x() == doctest::Approx(-1.0));
  CHECK(pair.box_max.x() == doctest::Approx(3.0));
  CHECK(pair.box_min.y() == doctest::Approx(-1.0));
  CHECK(pair.box_max.z() == doctest::Approx(1.0));
  CHECK(pair.body == 4);
  CHECK_FALSE(pair.mixed_bodies);
  CHECK(pair.smallest_id == 10);

  const Fragment& single = result.fragments[1];
  CHECK(single.particles == 1);
  CHECK(single.d_eq == doctest::Approx(1.0).epsilon(kTol));  // a sphere's d_eq is its diameter
  CHECK(single.centre.z() == doctest::Approx(5.0));
  CHECK(single.velocity.z() == doctest::Approx(-2.0));
  CHECK(single.body == 2);
}

TEST_CASE("a fragment bonded across bodies takes the body with the larger mass") {
  const std::vector<Index> id{0, 1, 2};
  const std::vector<Vec3> position{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<Vec3> velocity(3, Vec3::Zero());
  const std::vector<double> radius(3, 0.5);
  const std::vector<double> mass{1.0, 1.0, 3.0};
  const std::vector<std::int32_t> body{1, 1, 7};
  const std::vector<Index> bond_i{0, 1}, bond_j{1, 2};
  const FragmentAnalysis result =
      analyse_fragments({id, position, velocity, radius, mass, body}, {bond_i, bond_j});
  REQUIRE(result.fragments.size() == 1);
  CHECK(result.fragments[0].mixed_bodies);
  CHECK(result.fragments[0].body == 7);  // 3 kg of body 7 against 2 kg of body 1
}

TEST_CASE("without a body array every fragment comes from body 0") {
  const std::vector<Index> id{0, 1};
  const std::vector<Vec3> position{{0, 0, 0}, {1, 0, 0}};
  const std::vector<Vec3> velocity(2, Vec3::Zero());
  const std::vector<double> radius(2, 0.5);
  const std::vector<double> mass(2, 1.0);
  const FragmentAnalysis result = analyse_fragments({id, position, velocity, radius, mass, {}}, {});
  REQUIRE(result.fragments.size() == 2);
  CHECK(result.fragments[0].body == 0);
  CHECK(result.fragments[1].body == 0);
}

TEST_CASE("arrays of different lengths are rejected") {
  const std::vector<Index> id{0, 1};
  const std::vector<Vec3> position{{0, 0, 0}};
  const std::vector<Vec3> velocity(2, Vec3::Zero());
  const std::vector<double> radius(2, 0.5);
  const std::vector<double> mass(2, 1.0);
  CHECK_THROWS_AS(analyse_fragments({id, position, velocity, radius, mass, {}}, {}),
                  std::invalid_argument);
}
