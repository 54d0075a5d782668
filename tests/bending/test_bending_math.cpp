// Eq. 14 / 15 and the load-curve reduction on curves whose answers are known by hand.
#include <doctest/doctest.h>

#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

#include "shard/bending/beam_theory.hpp"
#include "shard/bending/curve_analysis.hpp"
#include "shard/analysis/quasi_static.hpp"

using namespace shard::bending;

TEST_CASE("eq. 14 and 15 for the seed's specimen, numbers worked by hand") {
  const BendingGeometry g{0.180, 0.080, 0.030, 0.035};
  // I = 0.030 * 0.035^3 / 12 = 1.071875e-7 m^4
  CHECK(g.second_moment() == doctest::Approx(1.071875e-7).epsilon(1e-12).scale(0));
  // w_s = F (L-d)^2 (L+2d) / (48 E I): F = 50 N, E = 13.2 MPa -> 50 * 0.01 * 0.34 / 67.914 = 2.50317 mm
  const double w = 50.0 * 0.01 * 0.34 / (48.0 * 13.2e6 * 1.071875e-7);
  CHECK(w == doctest::Approx(2.50317e-3).epsilon(1e-5).scale(0));
  CHECK(youngs_modulus_from_stiffness(g, 50.0 / w) == doctest::Approx(13.2e6).epsilon(1e-12));
  CHECK(stiffness_from_youngs_modulus(g, 13.2e6) == doctest::Approx(50.0 / w).epsilon(1e-12));
  // sigma_b = 3 F (L-d) / (2 b h^2) = 3 * 50 * 0.1 / (2 * 0.03 * 0.035^2) = 204 081.6 Pa
  CHECK(flexural_stress(g, 50.0) == doctest::Approx(204081.63).epsilon(1e-7));
  CHECK(force_from_flexural_stress(g, 204081.63) == doctest::Approx(50.0).epsilon(1e-7));
  // Timoshenko: E h^2 / (5/6 G (L-d)(L+2d)) = 2.5 * 1225 / (0.8333 * 100 * 340) = 0.1081
  CHECK(shear_to_bending_deflection(g, 2.5) == doctest::Approx(0.108088).epsilon(1e-4).scale(0));
}

TEST_CASE("geometry errors are refused with a message") {
  CHECK_THROWS_AS(BendingGeometry({0.08, 0.08, 0.03, 0.035}).check(), std::invalid_argument);
  CHECK_THROWS_AS(flexural_stress({0.18, 0.08, 0.0, 0.035}, 1.0), std::invalid_argument);
}

namespace {

// A lab-like curve: a quadratic toe (seating of the pins) until the line takes over, a linear
// part of stiffness k, softening over the last 20 % before F_max, then a brittle drop.
struct SyntheticCurve {
  std::vector<double> w, f;
};

SyntheticCurve synthetic(double k, double f_max, double toe, double dw) {
  SyntheticCurve c;
  // Toe: F = k (w - toe/2)... written so F and dF/dw are continuous at w = toe: F = k w^2 / (2 toe).
  const double w_lin_end = toe / 2 + 0.8 * f_max / k;  // linear F = k (w - toe/2) up to 0.8 F_max
  const double w_peak = w_lin_end + 0.4 * f_max / k;   // parabola from 0.8 F_max to F_max
  for (double w = 0; w < w_peak + 10 * dw; w += dw) {
    double f;
    if (w < toe)
      f = k * w * w / (2 * toe);
    else if (w < w_lin_end)
      f = k * (w - toe / 2);
    else if (w <= w_peak) {
      const double x = (w - w_lin_end) / (w_peak - w_lin_end);  // slope k at x = 0, zero at x = 1
      f = 0.8 * f_max + 0.2 * f_max * (2 * x - x * x);
    } else {
      f = 0.3 * f_max;  // broken
    }
    c.w.push_back(w);
    c.f.push_back(f);
  }
  return c;
}

}  // namespace

TEST_CASE("curve reduction: stiffness past the toe, F_max, w_s,max from the onset, eq. 14 / 15") {
  const BendingGeometry g{0.180, 0.080, 0.030, 0.035};
  const double k = stiffness_from_youngs_modulus(g, 13.2e6);  // ~19.98 N/mm
  const double f_max = 50.0, toe = 0.1e-3;
  // The toe ends at F = k toe / 2 ~ 1 N, i.e. 2 % of F_max: the 10-40 % window sees only the line.
  const auto c = synthetic(k, f_max, toe, 1e-6);
  const auto a = analyse_curve(c.w, c.f, g);
  CHECK(a.force_max == doctest::Approx(f_max).epsilon(1e-6));
  CHECK(a.stiffness == doctest::Approx(k).epsilon(1e-9));
  CHECK(a.fit.r_squared == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(a.onset == doctest::Approx(toe / 2).epsilon(1e-6).scale(0));
  CHECK(a.youngs_modulus == doctest::Approx(13.2e6).epsilon(1e-8));
  // w_s,max from the onset: 0.8 F/k + 0.4 F/k = 1.2 F_max / k; the sampling step is 1e-6 m.
  CHECK(a.deflection_at_peak == doctest::Approx(1.2 * f_max / k).epsilon(1e-6 / (1.2 * f_max / k)).scale(0));
  CHECK(a.youngs_modulus_secant == doctest::Approx(13.2e6 / 1.2).epsilon(2e-3));
  CHECK(a.flexural_strength == doctest::Approx(flexural_stress(g, f_max)));
  CHECK(a.failed);
}

TEST_CASE("curve reduction: a window that includes the toe lowers the stiffness, so the window matters") {
  const BendingGeometry g{0.180, 0.080, 0.030, 0.035};
  const double k = 2e4;
  const auto c = synthetic(k, 50.0, 1.5e-3, 1e-6);  // toe up to 15 N = 30 % of F_max
  CurveOptions early;
  early.fit_low = 0.0;
  early.fit_high = 0.3;
  CHECK(analyse_curve(c.w, c.f, g, early).stiffness < 0.8 * k);
  CurveOptions late;
  late.fit_low = 0.35;
  late.fit_high = 0.75;
  CHECK(analyse_curve(c.w, c.f, g, late).stiffness == doctest::Approx(k).epsilon(1e-9));
}

TEST_CASE("curve reduction: an unbroken curve is reported as not failed; bad input is refused") {
  const BendingGeometry g{0.180, 0.080, 0.030, 0.035};
  std::vector<double> w, f;
  for (int i = 0; i <= 100; ++i) w.push_back(1e-5 * i), f.push_back(3e4 * 1e-5 * i);
  const auto a = analyse_curve(w, f, g);
  CHECK_FALSE(a.failed);
  CHECK(a.stiffness == doctest::Approx(3e4));
  CHECK(a.peak_row == 100);
  const std::vector<double> zeros(5, 0.0);
  CHECK_THROWS_AS(analyse_curve(zeros, zeros, g), std::invalid_argument);
  CHECK_THROWS_AS(analyse_curve(std::vector<double>{0, 1}, std::vector<double>{0, 1, 2}, g), std::invalid_argument);
  // Two rows only: too few in the fit window.
  CHECK_THROWS_AS(analyse_curve(std::vector<double>{0, 1e-3}, std::vector<double>{0, 1}, g), std::invalid_argument);
}

TEST_CASE("smoothed peak: a one-row spike at the snap is averaged over the peak window") {
  const BendingGeometry g{0.180, 0.080, 0.030, 0.035};
  // Rows every 5 um: a line of 10 N/mm up to 40 N at 4 mm, a 40 N plateau to 4.1 mm with one row
  // at 50 N (the snap), then broken. The 25 um window holds 5 rows: (4 x 40 + 50) / 5 = 42 N.
  std::vector<double> w, f;
  for (int i = 0; i <= 800; ++i) w.push_back(5e-6 * i), f.push_back(1e4 * 5e-6 * i);
  for (int i = 801; i <= 820; ++i) w.push_back(5e-6 * i), f.push_back(i == 810 ? 50.0 : 40.0);
  for (int i = 821; i <= 830; ++i) w.push_back(5e-6 * i), f.push_back(5.0);
  const auto a = analyse_curve(w, f, g);
  CHECK(a.force_max == doctest::Approx(50.0));
  CHECK(a.force_max_smoothed == doctest::Approx(42.0).epsilon(1e-9));
  CurveOptions narrow;
  narrow.peak_window = 1e-6;  // one row: the raw maximum
  CHECK(analyse_curve(w, f, g, narrow).force_max_smoothed == doctest::Approx(50.0));
}

TEST_CASE("quasi-static figure: largest kinetic/elastic over the rows loaded to at least a fifth of the peak") {
  // Row 0 is seating (load 1 % of the peak, ratio 50), row 3 has no stored energy yet counted.
  const std::vector<double> load{0.1, 3.0, 10.0, 5.0};
  const std::vector<double> kinetic{5.0, 0.3, 0.1, 1.0};
  const std::vector<double> elastic{0.1, 1.0, 10.0, 0.0};
  CHECK(shard::analysis::max_kinetic_to_elastic(load, kinetic, elastic, 10.0) == doctest::Approx(0.3));
  // Only the rows the caller passes: before the first break, the kinetic series may be shorter.
  CHECK(shard::analysis::max_kinetic_to_elastic(load, std::span(kinetic).first(1), elastic, 10.0) == 0.0);
  CHECK(shard::analysis::max_kinetic_to_elastic(load, kinetic, elastic, 0.0) == 0.0);  // nothing loaded
}
