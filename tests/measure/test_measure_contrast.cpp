// The statistics of the contrast diagnosis (shard/measure/contrast.hpp) on cases with known
// answers: Hotelling's test against Student's t, the pooled covariance by hand, the components of
// an analytic curve, and the decision on differences made of known signatures.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "shard/measure/contrast.hpp"
#include "shard/measure/features.hpp"

using namespace shard::measure;

namespace {

std::vector<std::vector<double>> identity(std::size_t n) {
  std::vector<std::vector<double>> w(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) w[i][i] = 1;
  return w;
}

// A brittle test: linear rise F = k w to F_max, then a drop to zero over two readings.
Curve brittle(double k, double f_max, double dw) {
  Curve c;
  c.id = "analytic";
  const double w_peak = f_max / k;
  for (double w = 0; w <= w_peak * (1 + 1e-12); w += dw) {
    c.displacement.push_back(w);
    c.force.push_back(k * w);
  }
  c.displacement.push_back(w_peak + dw), c.force.push_back(0.4 * f_max);
  c.displacement.push_back(w_peak + 2 * dw), c.force.push_back(0.0);
  for (std::size_t i = 0; i < c.size(); ++i) c.time.push_back(static_cast<double>(i));
  c.u_displacement.assign(c.size(), 1e-7);
  c.u_force.assign(c.size(), 1e-3);
  return c;
}

// A rise that stiffens with the load, F = k w (1 + w / w0) (seating contacts that flatten), to
// a brittle drop at f_max.
Curve stiffening(double k, double w0, double f_max, double dw) {
  Curve c;
  c.id = "stiffening";
  double w = 0;
  for (; k * w * (1 + w / w0) <= f_max; w += dw) {
    c.displacement.push_back(w);
    c.force.push_back(k * w * (1 + w / w0));
  }
  c.displacement.push_back(w), c.force.push_back(0.3 * f_max);
  for (std::size_t i = 0; i < c.size(); ++i) c.time.push_back(static_cast<double>(i));
  c.u_displacement.assign(c.size(), 1e-7);
  c.u_force.assign(c.size(), 1e-3);
  return c;
}

}  // namespace

TEST_CASE("Hotelling's test of one component is Student's two-sided t test") {
  // t(0.975, 10) = 2.228139 (tables): T^2 = t^2 with nu = 10 has p = 0.05.
  CHECK(hotelling_p(2.228139 * 2.228139, 1, 10, 1) == doctest::Approx(0.05).epsilon(1e-4).scale(0));
  // More degrees of freedom approach the normal: t(0.975, 1e6) -> 1.959964.
  CHECK(hotelling_p(1.959964 * 1.959964, 1, 1e6, 1) == doctest::Approx(0.05).epsilon(1e-3).scale(0));
  CHECK(hotelling_p(0, 3, 20, 3) == 1.0);
  // Fewer specimens than components: the F test has no denominator degrees of freedom and the
  // chi-square(m) limit is used (P(chi^2(2) > 2 ln 20) = 0.05 exactly).
  CHECK(hotelling_p(2 * std::log(20.0), 2, 1, 2) == doctest::Approx(0.05).epsilon(1e-9));
}

TEST_CASE("the smallest T^2 the test sees at a level: the inverse of its p, and the t test's square") {
  CHECK(hotelling_critical(0.05, 1, 10, 1) == doctest::Approx(2.228139 * 2.228139).epsilon(1e-6));
  for (const auto& [k, nu] : {std::pair{8.0, 30.0}, std::pair{16.0, 9.0}, std::pair{8.0, 15.0}})
    CHECK(hotelling_p(hotelling_critical(0.05, k, nu, 8), k, nu, 8) == doctest::Approx(0.05).epsilon(1e-9));
  // A starved pool: 9 degrees of freedom for 8 components leave F(16, 2), whose 5 % point is
  // 19.43 (tables): T^2 1399, fifty times chi^2(16)'s 26.30.
  CHECK(hotelling_critical(0.05, 16, 9, 8) == doctest::Approx(9.0 * 16 / 2 * 19.43).epsilon(1e-3));
  CHECK(hotelling_critical(0.05, 2, 1, 2) == doctest::Approx(2 * std::log(20.0)).epsilon(1e-9));  // the chi^2 limit
}

// Null contrasts judged against an estimated scatter: p = 8 components, their covariance
// estimated from nu + 1 specimens (Sigma = identity), a difference d ~ N(0, A (x) Sigma) with
// A = [[2, 1], [1, 2]] / 4 at two rates (own mean and a shared reference) or 1 / 2 at one rate.
struct NullContrasts {
  NullContrasts(int rates_, int dof_, int draws_) : rates(rates_), dof(dof_), draws(draws_) {}
  int rates, dof, draws;
  std::mt19937 rng{20261205};
  std::normal_distribution<double> unit;

  std::vector<double> normals(std::size_t n) {
    std::vector<double> v(n);
    for (double& x : v) x = unit(rng);
    return v;
  }
  // The share of draws whose `p_of(decision)` falls below `level`, the effect a fixed direction.
  template <class P>
  double share_below(double level, P p_of) {
    const std::size_t m = 8;
    const std::vector<double> direction = normals(m * static_cast<std::size_t>(rates));
    const double inf = std::numeric_limits<double>::infinity();
    const std::vector<EffectSignature> effect{{"e", 1, direction, -inf, inf}};
    int below = 0;
    for (int k = 0; k < draws; ++k) {
      std::vector<std::vector<double>> rows;
      for (int r = 0; r <= dof; ++r) rows.push_back(normals(m));
      double nu = 0;
      const auto sigma = pooled_covariance({rows}, 0, nu);
      const std::size_t n = m * static_cast<std::size_t>(rates);
      std::vector<std::vector<double>> cov(n, std::vector<double>(n, 0.0));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          cov[i][j] = sigma[i % m][j % m] * (rates == 1 ? 0.5 : (i / m == j / m ? 0.5 : 0.25));
      // d = (chol(A) (x) I) z, so that its covariance is A (x) I.
      const std::vector<double> z = normals(n);
      std::vector<double> d(n);
      for (std::size_t i = 0; i < m; ++i) {
        if (rates == 1) {
          d[i] = std::sqrt(0.5) * z[i];
        } else {
          d[i] = std::sqrt(0.5) * z[i];
          d[m + i] = std::sqrt(0.125) * z[i] + std::sqrt(0.375) * z[m + i];
        }
      }
      if (p_of(decide_contrast(d, spd_inverse(cov), effect, {nu, static_cast<double>(m)})) < level) ++below;
    }
    return static_cast<double>(below) / draws;
  }
};

TEST_CASE("a chance direction is called significant as often as its level says") {
  // 20,000 null draws: a share of 0.01 has a binomial sd of 0.0007, so 0.0025 is 3.5 sd.
  NullContrasts one_rate{1, 15, 20000};
  CHECK(one_rate.share_below(0.01, [](const ContrastDecision& c) { return c.fits.front().p_drop; }) ==
        doctest::Approx(0.01).epsilon(0.25).scale(0));
  // The drop alone against F(1, nu - p + 1), the estimate's error left out, is 11 x too bold.
  NullContrasts bold{1, 15, 20000};
  const double old_rule = bold.share_below(0.01, [](const ContrastDecision& c) {
    return hotelling_p(c.fits.front().drop, 1, 15 - 8 + 1, 1);
  });
  CHECK(old_rule > 0.08);
  // At two rates on one estimate the tests err on the safe side, never the bold one.
  NullContrasts two_rates{2, 15, 20000};
  const double drops = two_rates.share_below(0.01, [](const ContrastDecision& c) { return c.fits.front().p_drop; });
  CHECK(drops < 0.0125);
  CHECK(drops > 0.001);
  NullContrasts differences{2, 15, 20000};
  const double t_square = differences.share_below(0.05, [](const ContrastDecision& c) { return c.p_value; });
  CHECK(t_square < 0.055);
  CHECK(t_square > 0.025);
}

TEST_CASE("pooled covariance: each group about its own mean, off-diagonal shrunk") {
  // Group 1: (0,0), (2,2): deviations (-1,-1), (1,1). Group 2: (10,0), (10,4): (0,-2), (0,2).
  // Sum of outer products: [[2, 2], [2, 10]], dof = 2, so [[1, 1], [1, 5]].
  double dof = 0;
  const auto s = pooled_covariance({{{0, 0}, {2, 2}}, {{10, 0}, {10, 4}}, {{7, 7}}}, 0.1, dof);
  CHECK(dof == 2);  // the one-specimen group adds nothing
  CHECK(s[0][0] == doctest::Approx(1));
  CHECK(s[1][1] == doctest::Approx(5));
  CHECK(s[0][1] == doctest::Approx(0.9));
  CHECK(s[1][0] == doctest::Approx(0.9));
  const auto inv = spd_inverse(s);
  CHECK(inv[0][0] * s[0][0] + inv[0][1] * s[1][0] == doctest::Approx(1));
  CHECK(inv[0][0] * s[0][1] + inv[0][1] * s[1][1] == doctest::Approx(0).epsilon(1e-12));
  CHECK_THROWS(spd_inverse({{1, 1}, {1, 1}}));
}

TEST_CASE("components of an analytic brittle curve") {
  const double k = 2e4, f_max = 40, dw = 1e-5;
  const Curve c = brittle(k, f_max, dw);
  const ContrastScale scale = contrast_scale({c});
  CHECK(scale.f_ref == doctest::Approx(f_max));
  CHECK(scale.w_ref == doctest::Approx(f_max / k).scale(0));
  const auto x = contrast_components(c);
  REQUIRE(x.size() == contrast_component_names().size());
  CHECK(x[0] == doctest::Approx(std::log(k)).epsilon(1e-9));          // the elastic fit of a line is exact
  CHECK(x[1] == doctest::Approx(std::log(f_max)));
  CHECK(x[2] == doctest::Approx(std::log(f_max / k)));
  CHECK(x[3] == doctest::Approx(std::log(0.5 * f_max * f_max / k)).epsilon(1e-6));  // trapezoids of a line
  CHECK(x[4] == doctest::Approx(0).epsilon(1e-9));                    // linear to the peak
  CHECK(x[5] == doctest::Approx(std::log((f_max / k + dw) / (f_max / k))).scale(0));  // 0.4 F_max < F_max / 2: parted at the first reading after the peak
  Curve flat = c;
  for (auto& f : flat.force) f = -f;
  CHECK_THROWS(contrast_components(flat));  // no rise: a sign convention error, said so
}

TEST_CASE("the contrast's stiffness is a chord between fixed loads: a higher peak on the same rise leaves it") {
  // One stiffening rise (slope 2e4 N/m at rest, 5x that at 40 N), broken at 40 N and at 52 N:
  // the same material, one stronger. Between the study's fixed loads (10-40 % of the reference's
  // 40 N) both have one slope, to the sampling's round-off; between 10 % and 60 % of each curve's
  // own peak the stronger one reads stiffer, and its nonlinearity moves with it.
  const double k = 2e4, w0 = 5e-4, dw = 1e-7;
  const Curve weak = stiffening(k, w0, 40, dw), strong = stiffening(k, w0, 52, dw);
  const StiffnessBand band = stiffness_band(contrast_scale({weak}));
  const double peak = weak.force[peak_index(weak)];  // the last sample below 40 N
  CHECK(band.low == doctest::Approx(0.1 * peak).scale(0));
  CHECK(band.high == doctest::Approx(0.4 * peak).scale(0));
  const auto a = contrast_components(weak, band), b = contrast_components(strong, band);
  CHECK(b[0] - a[0] == doctest::Approx(0).epsilon(1e-4));  // the rows differ by one sample at most
  const auto own_a = contrast_components(weak), own_b = contrast_components(strong);
  CHECK(own_b[0] - own_a[0] > 0.1);  // the own window climbs the rise: > +10 % in stiffness
  // A batch too weak for the band (peak 20 N < 16 / 0.6 N): its line is taken below 60 % of its
  // own peak, still on the rise (between 3 and 12 N: a slope between those of the rise there).
  const auto weakest = contrast_components(stiffening(k, w0, 20, dw), band);
  const auto slope_at = [&](double f) { return k * std::sqrt(1 + 4 * f / (k * w0)); };  // dF/dw at F
  CHECK(std::exp(weakest[0]) > slope_at(3));
  CHECK(std::exp(weakest[0]) < slope_at(12));
}

TEST_CASE("the line between fixed loads takes the rise's first passage: a slip and a second climb leave it") {
  // A straight rise of 2e4 N/m to 20 N, a slip back to 5 N at constant load-point speed, and a
  // second climb at half the slope to a 40 N peak. Between 4 and 16 N only the first passage
  // counts: its slope is the first rise's; all samples in that range together would mix both.
  Curve c;
  const double k = 2e4, dw = 1e-6;
  double w = 0, f = 0;
  const auto push = [&] {
    c.displacement.push_back(w), c.force.push_back(f);
  };
  for (; f < 20; w += dw, f = k * w) push();
  const double w_slip = w;
  for (; f > 5; w += dw) f = 20 - 1e4 * (w - w_slip), push();
  const double w_climb = w, f_climb = f;
  for (; f < 40; w += dw) f = f_climb + 0.5 * k * (w - w_climb), push();
  w += dw, f = 10, push();
  for (std::size_t i = 0; i < c.size(); ++i) c.time.push_back(static_cast<double>(i));
  c.u_displacement.assign(c.size(), 1e-7);
  c.u_force.assign(c.size(), 1e-3);
  const ElasticFit line = elastic_fit_between(c, 4, 16);
  CHECK(line.stiffness == doctest::Approx(k).epsilon(1e-6));
  CHECK(line.toe_offset == doctest::Approx(0).scale(1e-9));
}

TEST_CASE("decision: the effect that made the difference is named with its size") {
  const std::vector<double> a{1, 0.5, 0, 0}, b{0, 0, 1, -1};
  const auto w = identity(4);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<EffectSignature> effects{{"a", 1, a, 0, inf}, {"b", 1, b, 0, inf}};
  // d = 3 a + noise of unit scale: chi^2_0 = 11.25 + ..., the drop is 3^2 |a|^2.
  const std::vector<double> d{3.0 + 0.3, 1.5 - 0.2, 0.4, 0.5};
  const auto c = decide_contrast(d, w, effects, {40, 4});
  CHECK(c.verdict == "a");
  REQUIRE(c.fits.size() == 2);
  CHECK(c.fits.front().name == "a");
  // a = (3.3 + 0.65) / 1.25 = 3.16; what remains: d - a t.
  CHECK(c.fits.front().scale == doctest::Approx(3.16));
  CHECK(c.fits.front().u_scale == doctest::Approx(1 / std::sqrt(1.25)));
  CHECK(c.fits.front().p_after > 0.05);
  CHECK(c.fits.back().name == "b");
  CHECK(c.fits.back().at_bound);  // b would be wanted reversed: clamped to its neutral bound
  CHECK(c.fits.back().scale == 0.0);
  CHECK(c.rivals.empty());
}

TEST_CASE("decision: no difference, and a difference no effect explains") {
  const auto w = identity(4);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<EffectSignature> effects{{"a", 1, {1, 0.5, 0, 0}, 0, inf}, {"b", 1, {0, 0, 1, -1}, 0, inf}};
  CHECK(decide_contrast({0.5, -0.3, 0.2, 0.1}, w, effects, {40, 4}).verdict == kNoDifference);
  // Large, and orthogonal to both signatures: something outside the library.
  const auto c = decide_contrast({1.0, -2.0, 4.0, 4.0}, w, effects, {40, 4});
  CHECK(c.p_value < 1e-3);
  CHECK(c.verdict == kUnexplainedDifference);
  // Two effects that explain it equally are rivals.
  std::vector<EffectSignature> twins{{"a", 1, {1, 1, 0, 0}, 0, inf}, {"a2", 1, {1, 1, 0.01, 0}, 0, inf}};
  const auto t = decide_contrast({4.0, 4.1, 0.1, 0.0}, w, twins, {40, 4});
  CHECK((t.verdict == "a" || t.verdict == "a2"));
  CHECK(t.rivals.size() == 1);
}

TEST_CASE("decision: an effect of another form is named within the form tolerance, not beyond it") {
  const auto w = identity(4);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<EffectSignature> effects{{"a", 1, {4, 2, 1, 0}, 0, inf}};
  // The lab's effect: 2.5 x the library's shape, its third component 30 % off (another form).
  const std::vector<double> d{10.0, 5.0, 2.5 * 1.3, 0.0};
  ContrastOptions exact;
  exact.form_tolerance = 0;
  const auto strict = decide_contrast(d, w, effects, {60, 4}, exact);
  // a = (40 + 10 + 3.25) / 21 = 2.536; the third component misses by 0.71 of unit noise, the
  // others by -0.14 and -0.07: chi^2 after ~0.53, noise. A larger miss is needed to fail:
  CHECK(strict.verdict == "a");
  const std::vector<double> far{10.0, 5.0, 2.5 * 3.0, 0.0};  // third component 200 % off: 5 sigma
  const auto strict_far = decide_contrast(far, w, effects, {60, 4}, exact);
  CHECK(strict_far.verdict == kUnexplainedDifference);
  // With a 20 % form tolerance the third component's variance grows by (0.2 a t_3)^2 ~ 0.28: a
  // 5-sigma miss stays a miss, the model's shape is not stretched to fit anything.
  CHECK(decide_contrast(far, w, effects, {60, 4}).verdict == kUnexplainedDifference);
  // A miss of 40 % on a large component is 4 sigma without the tolerance, about 2 with it.
  const std::vector<double> shaped{4.0 * 5 * 1.4, 2.0 * 5, 1.0 * 5, 0.0};
  CHECK(decide_contrast(shaped, w, effects, {60, 4}, exact).verdict == kUnexplainedDifference);
  CHECK(decide_contrast(shaped, w, effects, {60, 4}).verdict == "a");
}

TEST_CASE("decision: a rate effect at one rate is never the verdict, a rival at most") {
  const auto w = identity(4);
  const double inf = std::numeric_limits<double>::infinity();
  // d = 3 a: "a" explains it exactly; "v" (a rate effect on a contrast of one rate) nearly as well.
  std::vector<EffectSignature> effects{{"a", 1, {1, 0.5, 0, 0}, 0, inf}, {"v", 1, {1, 0.52, 0, 0}, 0, inf, false}};
  const auto both = decide_contrast({3.0, 1.5, 0.1, -0.1}, w, effects, {40, 4});
  CHECK(both.verdict == "a");
  REQUIRE(both.rivals.size() == 1);
  CHECK(both.rivals.front() == "v");
  CHECK(both.unidentifiable.empty());
  // Only the rate effect fits: the difference stays unexplained, and the report names what would fit.
  effects.front().signature = {0, 0, 1, -1};
  const auto alone = decide_contrast({3.0, 1.56, 0.1, -0.1}, w, effects, {40, 4});
  CHECK(alone.verdict == kUnexplainedDifference);
  CHECK(alone.unidentifiable == "v");
  // The same effect with two rates behind the contrast is named.
  effects.back().identifiable = true;
  CHECK(decide_contrast({3.0, 1.56, 0.1, -0.1}, w, effects, {40, 4}).verdict == "v");
}

TEST_CASE("pair: two effects at once are sized jointly; the second is named only for what it adds") {
  const auto w = identity(6);
  const double inf = std::numeric_limits<double>::infinity();
  const EffectSignature a{"a", 1, {2, 1, 0, 0, 0.4, 0}, 0, inf}, b{"b", 1, {0.3, 0, 1, -1, 0, 0}, 0, inf},
      c{"c", 1, {0, 0, 0, 0, 0, 1}, 0, inf};
  // d = 4 a + 3 b + noise below one standard unit.
  const std::vector<double> d{8 + 0.9 + 0.2, 4 - 0.3, 3 + 0.1, -3 - 0.4, 1.6 + 0.3, -0.2};
  const auto single = decide_contrast(d, w, {a, b, c}, {60, 6});
  REQUIRE(single.fits.front().name == "a");
  CHECK(single.verdict == kUnexplainedDifference);  // a alone leaves b's 3 x sqrt(2) units
  const auto pair = fit_contrast_pair(d, w, a, b, single.fits.front().chi_square, {60, 6});
  // The joint least squares of d on (a, b): solved here from its 2 x 2 normal equations (Cramer).
  auto dot = [](const std::vector<double>& u, const std::vector<double>& v) {
    double s = 0;
    for (std::size_t i = 0; i < u.size(); ++i) s += u[i] * v[i];
    return s;
  };
  const double aa = dot(a.signature, a.signature), ab = dot(a.signature, b.signature), bb = dot(b.signature, b.signature),
               ad = dot(a.signature, d), bd = dot(b.signature, d), det = aa * bb - ab * ab;
  const double xa = (ad * bb - ab * bd) / det, xb = (aa * bd - ab * ad) / det;
  CHECK(pair.scale_first == doctest::Approx(xa).epsilon(1e-12));
  CHECK(pair.scale_second == doctest::Approx(xb).epsilon(1e-12));
  CHECK(!pair.at_bound);
  CHECK(pair.scale_first == doctest::Approx(4).epsilon(0.15));
  CHECK(pair.scale_second == doctest::Approx(3).epsilon(0.15));
  double rest = 0;
  for (int i = 0; i < 6; ++i) rest += std::pow(d[i] - xa * a.signature[i] - xb * b.signature[i], 2);
  CHECK(pair.chi_square == doctest::Approx(rest).epsilon(1e-12));
  CHECK(pair.drop == doctest::Approx(single.fits.front().chi_square - pair.chi_square));
  CHECK(pair.p_after > 0.05);
  CHECK(pair_is_named(pair, 2));
  // A second that adds nothing but noise is not named: c carries only the 0.2 of noise.
  const auto noise = fit_contrast_pair(d, w, a, c, single.fits.front().chi_square, {60, 6});
  CHECK(noise.scale_second == 0.0);  // it would be wanted reversed: held at its neutral bound
  CHECK(noise.at_bound);
  CHECK(!pair_is_named(noise, 2));
  // The sizes stay in their ranges: b capped at 1 leaves a to take what it can.
  EffectSignature capped = b;
  capped.scale_max = 1;
  const auto held = fit_contrast_pair(d, w, a, capped, single.fits.front().chi_square, {60, 6});
  CHECK(held.scale_second == 1.0);
  CHECK(held.at_bound);
  const double a_given_b = (ad - ab) / aa;
  CHECK(held.scale_first == doctest::Approx(a_given_b).epsilon(1e-12));
  CHECK(held.chi_square > pair.chi_square);
  // Judged on a simulated combined contrast (effects interact): the drop and remainder read it.
  std::vector<double> combined(6);
  for (int i = 0; i < 6; ++i) combined[i] = 4 * a.signature[i] + 3 * b.signature[i];
  const auto sim = judge_simulated_pair(d, w, combined, pair, single.fits.front().chi_square, {60, 6});
  double expected = 0;
  for (int i = 0; i < 6; ++i) expected += (d[i] - combined[i]) * (d[i] - combined[i]);
  CHECK(sim.chi_square == doctest::Approx(expected).epsilon(1e-12));
  CHECK(sim.scale_first == pair.scale_first);
  CHECK(pair_is_named(sim, 2));
  // The same pair whose move from the first effect's run the packing seeds do not agree on.
  ContrastPairFit redrawn = sim;
  redrawn.p_seeds = 0.2;
  CHECK_FALSE(pair_is_named(redrawn, 2));
}

TEST_CASE("pair: a second effect is sought only beside a closest that took three quarters of T^2") {
  // The figures of two sets of the default-size foreign study (flat-faced model, 11 effects).
  ContrastFit friction;  // a self-weight set's closest: roller friction, T^2 112.7 -> chi^2 50.6
  friction.chi_square = 50.59, friction.drop = 112.67 - 50.59, friction.p_drop = 8.6e-5;
  CHECK_FALSE(starts_a_pair(friction, 112.67, 11));  // 55 %: a stand-in, not a start
  ContrastFit compliance;  // a compliance + softening set's closest: the frame, 7799 -> 1079
  compliance.chi_square = 1078.9, compliance.drop = 7798.8 - 1078.9, compliance.p_drop = 1e-12;
  CHECK(starts_a_pair(compliance, 7798.8, 11));  // 86 %
  ContrastFit unsure = compliance;
  unsure.p_drop = 0.05 / 11;  // not below the level over the library
  CHECK_FALSE(starts_a_pair(unsure, 7798.8, 11));
  ContrastFit twin = compliance;
  twin.identifiable = false;
  CHECK_FALSE(starts_a_pair(twin, 7798.8, 11));
  ContrastOptions half;
  half.pair_first_share = 0.5;
  CHECK(starts_a_pair(friction, 112.67, 11, half));
}

TEST_CASE("seeds agree on a move: its projection on the residual, per seed, under Student's t") {
  const auto w = identity(3);
  const std::vector<double> residual{1, 0, 2};
  // Per seed r' W D: 2.1, 1.9, 2.0: mean 2, sd 0.1, t = 34.6 with 2 degrees of freedom.
  const std::vector<std::vector<double>> alike{{0.1, 5, 1}, {-0.1, -3, 1}, {0, 0, 1}};
  const double t = 2 / (0.1 / std::sqrt(3.0));
  // Student's t with 2 degrees of freedom in closed form: P(T > t) = (1 - t / sqrt(2 + t^2)) / 2.
  CHECK(seed_consistency_p(residual, w, alike) == doctest::Approx(0.5 * (1 - t / std::sqrt(2 + t * t))).epsilon(1e-9));
  CHECK(seed_consistency_p(residual, w, alike) < 1e-3);
  // A change that redraws the fracture: the seeds move the model either way (1.5, -1.0, 0.1).
  const std::vector<std::vector<double>> redrawn{{1.5, 0, 0}, {-1, 0, 0}, {0.1, 0, 0}};
  CHECK(seed_consistency_p(residual, w, redrawn) > 0.2);
  // A mean move away from the residual, or fewer than two seeds: nothing for the pair.
  CHECK(seed_consistency_p(residual, w, {{-1, 0, 0}, {-2, 0, 0}}) == 1.0);
  CHECK(seed_consistency_p(residual, w, {{1, 0, 0}}) == 1.0);
  // Every seed moves it alike: no scatter at all.
  CHECK(seed_consistency_p(residual, w, {{1, 0, 0}, {1, 0, 0}}) == 0.0);
}
