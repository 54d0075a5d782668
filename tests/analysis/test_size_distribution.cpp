// Fragment size distribution on hand-computed examples.
#include <doctest/doctest.h>

#include <numbers>

#include "shard/analysis/size_distribution.hpp"

using namespace shard::analysis;

namespace {
constexpr double kTol = 1e-12;
}

TEST_CASE("four equal masses: Q = 1/4, 1/2, 3/4, 1 and x50 lands exactly on d = 2") {
  const std::vector<double> d{3.0, 1.0, 4.0, 2.0};  // unsorted on purpose
  const std::vector<double> mass{1.0, 1.0, 1.0, 1.0};
  const SizeDistribution fsd = size_distribution(d, mass, 2.5);
  REQUIRE(fsd.points.size() == 4);
  CHECK(fsd.points[0].d == 1.0);
  CHECK(fsd.points[1].cumulative == 0.5);
  CHECK(fsd.points[3].cumulative == 1.0);
  CHECK(fsd.fragments == 4);
  CHECK(fsd.x50 == 2.0);                                    // Q(2) = 0.5 exactly
  CHECK(fsd.x10 == 1.0);                                    // 0.1 <= Q_1: the smallest size
  CHECK(fsd.x90 == doctest::Approx(3.6).epsilon(kTol));     // 3 + (0.9-0.75)/0.25 * (4-3)
  CHECK(fsd.fines_mass == 2.0);                             // d = 1 and 2 are below 2.5
  CHECK(fsd.fines_fraction() == 0.5);
}

TEST_CASE("single spheres of radius 1, 2, 3: mass-weighted, masses 1 : 8 : 27") {
  const double rho = 2500.0;
  std::vector<double> d, mass;
  for (double r : {1.0, 2.0, 3.0}) {
    d.push_back(2 * r);
    mass.push_back(rho * 4.0 / 3.0 * std::numbers::pi * r * r * r);
  }
  const SizeDistribution fsd = size_distribution(d, mass);
  // Q = 1/36 at d=2, 9/36 at d=4, 1 at d=6.
  CHECK(fsd.points[0].cumulative == doctest::Approx(1.0 / 36).epsilon(kTol));
  CHECK(fsd.points[1].cumulative == doctest::Approx(9.0 / 36).epsilon(kTol));
  CHECK(fsd.x10 == doctest::Approx(2.0 + (0.1 - 1.0 / 36) / (8.0 / 36) * 2.0).epsilon(kTol));
  CHECK(fsd.x50 == doctest::Approx(4.0 + (0.5 - 0.25) / 0.75 * 2.0).epsilon(kTol));
  CHECK(fsd.x90 == doctest::Approx(4.0 + (0.9 - 0.25) / 0.75 * 2.0).epsilon(kTol));
  CHECK(fsd.fines_mass == 0.0);
  CHECK(fsd.total_mass == doctest::Approx(rho * 36 * 4.0 / 3.0 * std::numbers::pi).epsilon(kTol));
}

TEST_CASE("fragments of equal size merge into one point; one size gives x10 = x50 = x90") {
  const std::vector<double> d{0.02, 0.02, 0.02};
  const std::vector<double> mass{1.0, 2.0, 3.0};
  const SizeDistribution fsd = size_distribution(d, mass);
  REQUIRE(fsd.points.size() == 1);
  CHECK(fsd.points[0].cumulative == 1.0);
  CHECK(fsd.x10 == 0.02);
  CHECK(fsd.x50 == 0.02);
  CHECK(fsd.x90 == 0.02);
  CHECK(fsd.fragments == 3);
}

TEST_CASE("empty input gives an empty distribution; bad input is rejected") {
  const SizeDistribution fsd = size_distribution(std::vector<double>{}, std::vector<double>{});
  CHECK(fsd.points.empty());
  CHECK(fsd.fragments == 0);
  CHECK_THROWS_AS(size_distribution(std::vector<double>{1.0}, std::vector<double>{-1.0}),
                  std::invalid_argument);
  CHECK_THROWS_AS(characteristic_size(fsd.points, 0.0), std::invalid_argument);
}
