// Weibull strength scatter: 1e4 bond strengths drawn by the model follow the Weibull law of the
// given modulus and mean (Kolmogorov-Smirnov), are reproducible and order-independent, and each
// bond breaks at its own strength.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "beam_effects_setup.hpp"
#include "effects/bond_effects.hpp"
#include "effects/weibull_strength.hpp"

namespace shard::effects_test {
namespace {

// A chain of n + 1 spheres, n bonds; returns the strengths the model stored.
std::vector<double> chain_strengths(const beam::BeamBond& model, std::size_t n, bool reversed = false) {
  BondScene s;
  for (std::size_t k = 0; k <= n; ++k) s.add_sphere(Vec3(0.7e-3 * static_cast<double>(k), 0, 0), 0.35e-3);
  for (std::size_t k = 0; k < n; ++k) {
    const auto a = static_cast<Index>(k), b = static_cast<Index>(k + 1);
    if (reversed) s.add_bond(b, a);
    else s.add_bond(a, b);
  }
  s.initialize(model);
  std::vector<double> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = s.state[k * model.state_size() + beam::kStrengthSlot];
  return out;
}

// Two-sided Kolmogorov-Smirnov statistic of a sample against a CDF.
template <class Cdf>
double ks_statistic(std::vector<double> x, Cdf cdf) {
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double f = cdf(x[k]);
    d = std::max({d, f - static_cast<double>(k) / n, static_cast<double>(k + 1) / n - f});
  }
  return d;
}

}  // namespace

TEST_CASE("1e4 bond strengths follow the Weibull law with the set mean and modulus") {
  const std::size_t n = 10000;
  // Critical value of D at significance 0.001: 1.95 / sqrt(n) = 0.0195.
  const double d_critical = 1.95 / std::sqrt(static_cast<double>(n));
  for (const double m : {2.0, 5.0, 12.0}) {
    auto p = table_one_params();
    p.effects.strength_weibull_modulus = m;
    p.effects.strength_seed = 42;
    const beam::BeamBond model(p);
    const std::vector<double> strengths = chain_strengths(model, n);
    const double scale = beam::weibull_scale(p.critical_stress, m);
    const double d = ks_statistic(strengths, [&](double s) { return beam::weibull_cdf(s, scale, m); });
    MESSAGE("m = ", m, ": KS D = ", d, " (critical ", d_critical, ")");
    CHECK(d < d_critical);
    // Power of the test: the law with the scale mistaken for the mean is rejected.
    const double d_wrong = ks_statistic(strengths, [&](double s) {
      return beam::weibull_cdf(s, p.critical_stress, m);
    });
    CHECK(d_wrong > d_critical);

    // Sample mean within 4 standard errors of critical_stress; std = mean sqrt(G(1+2/m)/G(1+1/m)^2 - 1).
    double sum = 0;
    for (double s : strengths) sum += s;
    const double mean = sum / static_cast<double>(n);
    const double g1 = std::tgamma(1 + 1 / m), g2 = std::tgamma(1 + 2 / m);
    const double stddev = p.critical_stress * std::sqrt(g2 / (g1 * g1) - 1);
    CHECK(std::abs(mean - p.critical_stress) < 4 * stddev / std::sqrt(static_cast<double>(n)));
  }
}

TEST_CASE("strengths are common random numbers: same per bond whatever the listing order, new with a new seed") {
  auto p = table_one_params();
  p.effects.strength_weibull_modulus = 5;
  p.effects.strength_seed = 3;
  const beam::BeamBond model(p);
  const auto forward = chain_strengths(model, 1000);
  const auto again = chain_strengths(model, 1000);
  const auto reversed = chain_strengths(model, 1000, true);
  CHECK(forward == again);
  CHECK(forward == reversed);

  p.effects.strength_seed = 4;
  const auto other = chain_strengths(beam::BeamBond(p), 1000);
  // Independent draws: the sample correlation of the two seeds is O(1/sqrt(n)) = 0.03.
  double ma = 0, mb = 0;
  for (std::size_t k = 0; k < 1000; ++k) ma += forward[k] / 1000, mb += other[k] / 1000;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t k = 0; k < 1000; ++k) {
    sab += (forward[k] - ma) * (other[k] - mb);
    saa += (forward[k] - ma) * (forward[k] - ma);
    sbb += (other[k] - mb) * (other[k] - mb);
  }
  CHECK(std::abs(sab / std::sqrt(saa * sbb)) < 0.12);  // 4 sigma of a zero correlation
}

TEST_CASE("modulus 0 gives every bond exactly critical_stress") {
  auto p = table_one_params();
  p.effects.named = {"weibull_strength"};  // the policy in the law, at its neutral value
  const beam::BeamBond model(p);
  REQUIRE(model.with_effects());
  for (double s : chain_strengths(model, 100)) CHECK(s == 0.24e6);
}

TEST_CASE("a pulled bond breaks at its own drawn strength") {
  auto p = table_one_params();
  p.effects.strength_weibull_modulus = 3;
  p.effects.strength_seed = 11;
  const beam::BeamBond model(p);
  Pair pair(model);
  const double strength = pair.scene.state[beam::kStrengthSlot];
  CHECK(strength != doctest::Approx(p.critical_stress).epsilon(1e-3));
  const double E = p.youngs_modulus;
  pair.set(strength / E * (1 - 1e-9));
  pair.axial_force(model);
  CHECK_FALSE(pair.broken());
  pair.set(strength / E * (1 + 1e-9));
  pair.axial_force(model);
  CHECK(pair.broken());
  CHECK(pair.scene.stress[0].sigma_vm == doctest::Approx(strength).epsilon(1e-8));
}

TEST_CASE("the law given by its scatter: strength_cv is the coefficient of variation of the stored strengths") {
  // Closed forms: m = 1 is the exponential law (cv 1); m = 2 the Rayleigh law, cv sqrt(4 / pi - 1).
  CHECK(beam::weibull_cv(1.0) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(beam::weibull_cv(2.0) == doctest::Approx(std::sqrt(4 / M_PI - 1)).epsilon(1e-12));
  for (const double m : {0.6, 1.0, 2.0, 4.0, 12.0, 300.0})
    CHECK(beam::weibull_modulus_for_cv(beam::weibull_cv(m)) == doctest::Approx(m).epsilon(1e-9));
  // The same law two ways: strengths equal to rounding.
  auto by_modulus = table_one_params(), by_cv = table_one_params();
  by_modulus.effects.strength_weibull_modulus = 2;
  by_cv.effects.strength_cv = std::sqrt(4 / M_PI - 1);
  by_modulus.effects.strength_seed = by_cv.effects.strength_seed = 7;
  const auto a = chain_strengths(beam::BeamBond(by_modulus), 10000);
  const auto b = chain_strengths(beam::BeamBond(by_cv), 10000);
  double worst = 0, sum = 0, sum2 = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    worst = std::max(worst, std::abs(b[k] / a[k] - 1));
    sum += b[k], sum2 += b[k] * b[k];
  }
  CHECK(worst < 1e-9);
  // The sample's cv: 0.523 within 4 of its standard errors (~0.004 for n = 1e4 at this shape).
  const double n = static_cast<double>(b.size()), mean = sum / n;
  const double cv = std::sqrt(sum2 / n - mean * mean) / mean;
  CHECK(cv == doctest::Approx(by_cv.effects.strength_cv).epsilon(0.03).scale(0));
  // Both at once is a contradiction, not a precedence rule.
  shard::ParamSet both;
  for (const auto& spec : beam::bond_effect_params()) {
    if (const auto* x = std::get_if<double>(&spec.default_value)) both.set(spec.name, *x);
    if (const auto* t = std::get_if<std::string>(&spec.default_value)) both.set(spec.name, *t);
  }
  REQUIRE_NOTHROW(beam::BondEffects::from(both));
  both.set("strength_weibull_modulus", 2.0);
  both.set("strength_cv", 0.5);
  CHECK_THROWS_WITH(beam::BondEffects::from(both), doctest::Contains("keep one"));
}

}  // namespace shard::effects_test
