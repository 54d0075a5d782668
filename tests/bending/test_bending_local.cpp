// Local instrumentation (the beam's own deflection and curvature), the rate check's verdicts and
// a measurement file's set-up lines, on cases with answers known by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "shard/bending/local_deflection.hpp"
#include "shard/bending/network_stiffness.hpp"
#include "shard/bending/rate_check.hpp"

using namespace shard;
using namespace shard::bending;

namespace {

const BendingGeometry kBeam{0.170, 0.080, 0.030, 0.035};

// Euler-Bernoulli deflection of the four-point beam (total force F, F/2 per pin) at s from the
// centre; x is the distance from the nearer support, a the shear span.
double deflection(double s, double force, double ei) {
  const double span = kBeam.span, a = kBeam.shear_span(), p = 0.5 * force;
  const double x = 0.5 * span - std::abs(s);
  if (x <= a) return p * x * (3 * span * a - 3 * a * a - x * x) / (6 * ei);
  return p * a * (3 * span * x - 3 * x * x - a * a) / (6 * ei);
}

struct Grid {
  std::vector<Vec3> reference;
  Grid() {
    // 5 mm spacing: the stations s = +-40 and +-85 mm are grid lines; z from 0 to 35 mm.
    for (int i = -17; i <= 17; ++i)
      for (int j = -2; j <= 2; ++j)
        for (int k = 0; k <= 7; ++k) reference.emplace_back(0.005 * i, 0.005 * j, 0.005 * k);
  }
};

SectionGauges gauges(double section_width) {
  SectionGauges g;
  g.centre = Vec3(0, 0, 0.0175);
  g.axis = Vec3::UnitX();
  g.down = -Vec3::UnitZ();
  g.section_width = section_width;
  g.core_height = 0.5 * kBeam.height;
  return g;
}

}  // namespace

TEST_CASE("local deflection: eq. 14's w_s, free of the beam settling on its supports and of pin indentation") {
  const Grid grid;
  const double force = 40.0, ei = 9e6 * kBeam.second_moment();
  const double settle = 0.8e-3;  // the whole beam sinks into the supports' Hertz contacts
  std::vector<Vec3> deformed;
  for (const auto& p : grid.reference) {
    double u = deflection(p.x(), force, ei) + settle;
    if (p.z() > 0.030 && std::abs(std::abs(p.x()) - 0.040) < 0.006) u += 0.5e-3;  // crushed under the pins
    deformed.push_back(p - u * Vec3::UnitZ());
  }
  const double expected = force * std::pow(kBeam.span - kBeam.pin_distance, 2) * (kBeam.span + 2 * kBeam.pin_distance) /
                          (48 * ei);  // eq. 14: 3.7357 mm here
  CHECK(local_deflection(grid.reference, deformed, gauges(0.004), kBeam) == doctest::Approx(expected).epsilon(1e-12));
  // Sections three particles wide read a curved line through a straight one: within 0.5 % of
  // the station value, also over the supports, where the beam's end cuts the band one-sided.
  CHECK(local_deflection(grid.reference, deformed, gauges(0.0115), kBeam) == doctest::Approx(expected).epsilon(0.005).scale(0));
  auto between_grid_lines = gauges(0.001);
  between_grid_lines.centre.x() = 0.0025;  // stations half a spacing off the grid: empty sections
  CHECK_THROWS_AS(local_deflection(grid.reference, deformed, between_grid_lines, kBeam), std::invalid_argument);
}

TEST_CASE("local deflection: a one-sided band over a support reads the station, not the band's mean") {
  // The grid ends at the support stations (+-85 mm), so each support band holds particles on
  // one side only (s = 80, 85 mm), where the sag has its largest slope: a plain mean would read
  // w(82.5 mm), 6 % of w_s. On top, a rigid rotation u = 0.01 (s + 0.085).
  const Grid grid;
  const double force = 40.0, ei = 9e6 * kBeam.second_moment();
  std::vector<Vec3> deformed;
  for (const auto& p : grid.reference) deformed.push_back(p - (0.01 * (p.x() + 0.085) + deflection(p.x(), force, ei)) * Vec3::UnitZ());
  const double expected = force * std::pow(kBeam.span - kBeam.pin_distance, 2) * (kBeam.span + 2 * kBeam.pin_distance) /
                          (48 * ei);
  // The rotation moves both the pins' and the supports' mean by 0.01 * 0.085: it cancels.
  CHECK(local_deflection(grid.reference, deformed, gauges(0.0115), kBeam) == doctest::Approx(expected).epsilon(0.005).scale(0));
}

TEST_CASE("local instrumentation fit: stiffness and curvature modulus over the elastic frames") {
  // Frames of a beam with E = 9 MPa under F = 0 ... 50 N (F_max 50 N): w_local = F / k, kappa = M / EI.
  const double e = 9e6, ei = e * kBeam.second_moment();
  const double k = stiffness_from_youngs_modulus(kBeam, e);
  std::vector<LocalFrame> frames;
  for (int n = 0; n <= 50; ++n) {
    LocalFrame f;
    f.force = n;
    f.deflection = f.force / k + 1e-5;  // a constant offset: the fit is a line, not through the origin
    f.curvature = 0.5 * f.force * kBeam.shear_span() / ei;
    frames.push_back(f);
  }
  const auto r = fit_local_instrumentation(frames, kBeam, 50.0, CurveOptions{});
  REQUIRE(r.valid);
  CHECK(r.fit_frames == 16);  // F = 5 ... 20 N, 10-40 % of 50 N
  CHECK(r.youngs_modulus == doctest::Approx(e).epsilon(1e-9));
  CHECK(r.curvature_modulus == doctest::Approx(e).epsilon(1e-9));
  // A reference force moves the window: 10-40 % of 100 N holds F = 10 ... 40 N.
  CurveOptions reference;
  reference.reference_force = 100.0;
  CHECK(fit_local_instrumentation(frames, kBeam, 50.0, reference).fit_frames == 31);
  frames.resize(6);  // F <= 5 N: one frame in the window
  CHECK_FALSE(fit_local_instrumentation(frames, kBeam, 50.0, CurveOptions{}).valid);
}

TEST_CASE("curvature of a parabolic deflection line between the pins gives E = M / (kappa I)") {
  const Grid grid;
  const double force = 30.0, ei = 7e6 * kBeam.second_moment();
  std::vector<Vec3> deformed;
  for (const auto& p : grid.reference) deformed.push_back(p - deflection(p.x(), force, ei) * Vec3::UnitZ());
  const auto c = curvature_modulus(grid.reference, deformed, Vec3(0, 0, 0.0175), Vec3::UnitX(), -Vec3::UnitZ(), kBeam,
                                   force);
  REQUIRE(c.valid);
  CHECK(c.youngs_modulus == doctest::Approx(7e6).epsilon(1e-9));
}

TEST_CASE("beam-theory prediction of the local stiffness: eq. 14 plus Timoshenko shear") {
  // nu = 0.25: E/G = 2.5, shear/bending = 2.5 * 35^2 / (5/6 * 90 * 330) = 0.12374 on the 170 mm span.
  const double k = predicted_local_stiffness(kBeam, 10e6, 0.25);
  CHECK(k == doctest::Approx(stiffness_from_youngs_modulus(kBeam, 10e6) / 1.123737).epsilon(1e-5));
}

TEST_CASE("rate check verdicts on F_max and stiffness changes") {
  CurveAnalysis fast, slow;
  fast.force_max = 40.0, fast.stiffness = 10e3, fast.failed = true, fast.deflection_at_peak = 4e-3;
  slow = fast;
  slow.force_max = 39.0;   // -2.5 %
  slow.stiffness = 10.1e3;  // +1 %
  auto c = compare_rates(fast, slow);
  CHECK(c.force_max_change == doctest::Approx(-0.025).scale(0));
  CHECK(c.stiffness_change == doctest::Approx(0.01).scale(0));
  CHECK(c.passed());
  slow.stiffness = 9.7e3;  // -3 %
  c = compare_rates(fast, slow);
  CHECK(c.force_max_ok);
  CHECK_FALSE(c.stiffness_ok);
  CHECK_FALSE(c.passed());
  slow.stiffness = 10e3;
  slow.failed = false;  // the slow run stopped before breaking: its F_max is no strength
  CHECK_FALSE(compare_rates(fast, slow).passed());
  slow.force_max = 0;
  CHECK_THROWS_AS(compare_rates(fast, slow), std::invalid_argument);
}

TEST_CASE("a measurement file's '#!' set-up lines") {
  const std::string path = "bending_metadata_test.csv";
  {
    std::ofstream f(path);
    f << "# made by hand for this test\n#! span_mm = 170\n#! displacement = local\ndisplacement_mm,force_N\n0,0\n1,10\n";
  }
  const auto meta = read_curve_metadata(path);
  CHECK(meta.at("span_mm") == "170");
  CHECK(meta.at("displacement") == "local");
  CHECK(meta.size() == 2);
  const auto curve = read_curve_csv(path);
  CHECK(curve.displacement.at(1) == doctest::Approx(1e-3).scale(0));
  {
    std::ofstream f(path);
    f << "#! span_mm 170\ndisplacement_mm,force_N\n0,0\n";
  }
  CHECK_THROWS_AS(read_curve_metadata(path), std::runtime_error);
  std::remove(path.c_str());
}
