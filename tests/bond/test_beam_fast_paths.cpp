// The shortcuts the beam bond's step takes (docs/explanation/performance.md) against the exact expressions
// they replace: the arcsin series for mu and mu_axis, the square-root-free normalisation of a
// near-unit quaternion, and the bound that skips the von Mises square roots.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "beam_law.hpp"
#include "beam_stress.hpp"

using namespace shard;
using namespace shard::beam;

namespace {

// mu = asin(s) / s in long double (64-bit mantissa on x86), the closed form the series replaces.
long double exact_mu(long double s) { return std::asin(s) / s; }

// mu_axis = (1 - mu) / s^2 = -(c_1 + c_2 s^2 + ...) summed to 40 terms in long double, with the
// coefficients from their recurrence c_{n+1} = c_n (2n+1)^2 / ((2n+2)(2n+3)), independent of the
// hard-coded ones (the closed form (s - asin s) / s^3 cancels catastrophically at small s).
long double exact_mu_axis(long double s) {
  long double c = 1.0L / 6, power = 1, sum = 0;
  for (int n = 1; n <= 40; ++n) {
    sum += c * power;
    power *= s * s;
    c *= static_cast<long double>((2 * n + 1) * (2 * n + 1)) / static_cast<long double>((2 * n + 2) * (2 * n + 3));
  }
  return -sum;
}

}  // namespace

TEST_CASE("arcsin series: mu and mu_axis to 1e-15 relative over the whole series range") {
  // Geometric grid of s = sin(|theta|/2) from 1e-8 up to the switch s^2 = kSeriesLimit.
  double worst_mu = 0, worst_axis = 0;
  for (double s = 1e-8; s * s < kSeriesLimit; s *= 1.01) {
    const double s2 = s * s;
    const double tail = arcsin_ratio_tail(s2);
    const double mu = 1 + s2 * tail, mu_axis = -tail;
    const long double ls = s;
    const long double ref_axis = exact_mu_axis(ls);
    worst_mu = std::max(worst_mu, static_cast<double>(std::abs((mu - exact_mu(ls)) / exact_mu(ls))));
    worst_axis = std::max(worst_axis, static_cast<double>(std::abs((mu_axis - ref_axis) / ref_axis)));
  }
  CHECK(worst_mu < 1e-15);
  CHECK(worst_axis < 1e-15);
}

TEST_CASE("rotation_factors: the series and the atan2 branch meet without a step at the switch") {
  // q_rel = exp(theta / 2) of a twist by theta: v = (s, 0, 0), w = cos(theta / 2); theta must come
  // back as 2 mu s on either side of s^2 = kSeriesLimit, at width 1 (which takes atan2 beyond it).
  const double s_switch = std::sqrt(kSeriesLimit);
  for (const double s : {s_switch * (1 - 1e-9), s_switch * (1 + 1e-9), 1e-3, 0.3, 0.9}) {
    const double angle = 2 * std::asin(s);
    const double w = std::cos(angle / 2);
    double mu = 0, mu_axis = 0;
    const bool series = rotation_factors<double, true>(s * s, w, mu, mu_axis);
    CHECK(series == (s * s < kSeriesLimit));
    CHECK(2 * mu * s == doctest::Approx(angle).epsilon(1e-14));
    // M on theta itself: mu + mu_axis s^2 = 1 exactly in exact arithmetic.
    CHECK((mu + mu_axis * s * s) == doctest::Approx(1.0).epsilon(1e-14));
  }
}

TEST_CASE("inverse_norm: 1 / |q| for near-unit and for general quaternions") {
  bool unit = false;
  for (int ulps = -8; ulps <= 8; ++ulps) {
    const double n2 = 1 + ulps * 2.220446049250313e-16;
    CHECK(inverse_norm<double, true>(n2, unit) == doctest::Approx(1 / std::sqrt(n2)).epsilon(3e-16).scale(0));  // one ulp
    CHECK(unit);
  }
  CHECK(inverse_norm<double, true>(4.0, unit) == 0.5);
  CHECK_FALSE(unit);
  CHECK(inverse_norm<double, true>(0.25, unit) == 2.0);
  CHECK(inverse_norm<double, true>(1 + 1e-6, unit) == doctest::Approx(1 / std::sqrt(1 + 1e-6)).epsilon(3e-16).scale(0));
}

TEST_CASE("may_reach: never false when stress_of reaches the strength, false well below it") {
  const double E = 12.8e6, G = E / 2.5, r = 0.4e-3, strength = 0.24e6;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int reached = 0, skipped_below_half = 0, below_half = 0;
  for (int k = 0; k < 200000; ++k) {
    // Strains around the failure strain sigma/E ~ 0.019, curvatures around strain / r.
    const double scale = 0.04 * std::abs(u(rng));
    const double strain[3] = {scale * u(rng), scale * u(rng), scale * u(rng)};
    const double curvature[3] = {(scale / r) * u(rng), (scale / r) * u(rng), (scale / r) * u(rng)};
    const double vm = stress_of(strain, curvature, E, G, r).sigma_vm;
    const bool may = may_reach<double>(strain, curvature, E, G, r, strength);
    if (vm >= strength) {
      ++reached;
      REQUIRE(may);
    }
    if (vm < 0.5 * strength) {
      ++below_half;
      if (!may) ++skipped_below_half;
    }
  }
  CHECK(reached > 10000);
  // |a| + |b| <= sqrt(2) |(a, b)| makes the bound at most sqrt(2) sigma_vm: every state below
  // strength / sqrt(2) is ruled out without square roots (else the shortcut would save nothing).
  CHECK(below_half > 10000);
  CHECK(skipped_below_half == below_half);
  // Exactly at the strength (a one-plane bending state, where the bound is tight) it must not skip.
  const double strain[3] = {0, 0, 0};
  const double curvature[3] = {0, strength / (E * r), 0};
  CHECK(stress_of(strain, curvature, E, G, r).sigma_vm >= strength * (1 - 1e-15));
  CHECK(may_reach<double>(strain, curvature, E, G, r, strength));
}
