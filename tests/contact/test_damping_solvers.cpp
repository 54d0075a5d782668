// The restitution-to-damping solvers inside the plugins, checked against independent integrations.
#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>

#include "../../plugins/contact/hertz_mindlin/hertz_damping.hpp"
#include "../../plugins/contact/linear_spring/linear_damping.hpp"

namespace {

// The clamped linear oscillator x'' = -max(0, x + 2 zeta x') by explicit midpoint steps: a second
// method, so the closed form is checked against something that shares none of its algebra.
double brute_force_linear_restitution(double zeta) {
  const double h = 1e-5;
  double x = 0.0, u = 1.0;
  auto accel = [zeta](double xx, double uu) { return -std::fmax(0.0, xx + 2.0 * zeta * uu); };
  for (int step = 0; step < 10'000'000; ++step) {
    const double xm = x + 0.5 * h * u;
    const double um = u + 0.5 * h * accel(x, u);
    x += h * um;
    u += h * accel(xm, um);
    if (x < 0.0) return -u;
  }
  return 0.0;
}

}  // namespace

TEST_CASE("Hertz: e(c) is converged in the step, inverts exactly, and differs from the textbook") {
  for (double c : {0.05, 0.5, 2.0}) {
    CAPTURE(c);
    CHECK(std::abs(shard::hertz::restitution_for_damping(c) - shard::hertz::restitution_for_damping(c, 2e-5)) <= 2e-6);
  }
  CHECK(shard::hertz::restitution_for_damping(0.0) == doctest::Approx(1.0).epsilon(1e-9));
  for (double e : {0.1, 0.3, 0.5, 0.9}) {
    CAPTURE(e);
    const double c = shard::hertz::damping_for_restitution(e);
    CHECK(std::abs(shard::hertz::restitution_for_damping(c) - e) <= 1e-10);
  }
  // Values of the clamped equation (h = 2e-5): c = 0.46607 for e = 0.5, where the textbook
  // 2 sqrt(5/6) beta gives 0.3934 (realising e = 0.55).
  CHECK(shard::hertz::damping_for_restitution(0.5) == doctest::Approx(0.46607).epsilon(1e-4).scale(0));
}

TEST_CASE("linear: the closed-form restitution of the clamped oscillator matches an integration") {
  // Under-, critically and over-damped.
  for (double zeta : {0.0, 0.1, 0.5, 0.999, 1.0, 1.001, 1.5, 3.0}) {
    CAPTURE(zeta);
    CHECK(std::abs(shard::linear::restitution_for_damping_ratio(zeta) - brute_force_linear_restitution(zeta)) <= 1e-8);
  }
  CHECK(shard::linear::restitution_for_damping_ratio(1.0) == doctest::Approx(std::exp(-2.0)).epsilon(1e-14));
  for (double e : {0.05, 0.3, 0.5, 0.9, 1.0}) {
    CAPTURE(e);
    const double zeta = shard::linear::damping_ratio_for_restitution(e);
    CHECK(std::abs(shard::linear::restitution_for_damping_ratio(zeta) - e) <= 1e-12);
  }
}
