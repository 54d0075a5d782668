// The foreign spring bond's hidden effects (spring_effects.hpp): a median-1 Weibull strength
// factor, parabolic softening past the peak load ratio, a stiffer normal spring in compression,
// subcritical damage (a rate-dependent strength), the pull of a failed bond (cohesion);
// and, through the plugin file, each at its declared neutral value leaves every output unchanged.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "../../bond/random_bonds.hpp"
#include "shard/plugin_host.hpp"
#include "spring_effects.hpp"
#include "spring_pair.hpp"

namespace shard::foreign_test {

using foreign::SpringBond;

TEST_CASE("strength scatter: a median-1 Weibull factor per bond, from the particle ids") {
  const double m = 4;
  const int n = 10000;
  std::vector<double> f;
  for (int k = 0; k < n; ++k) f.push_back(foreign::strength_factor(m, 2 * k, 2 * k + 1, 0));
  // The same bond listed the other way round draws the same factor; another seed another one.
  CHECK(foreign::strength_factor(m, 7, 3, 0) == foreign::strength_factor(m, 3, 7, 0));
  CHECK(foreign::strength_factor(m, 7, 3, 1) != foreign::strength_factor(m, 7, 3, 0));
  CHECK(foreign::strength_factor(0, 7, 3, 0) == 1.0);
  std::sort(f.begin(), f.end());
  // Kolmogorov-Smirnov against F(x) = 1 - 2^(-x^m): critical D at the 0.1 % level 1.95 / sqrt(n).
  double d = 0;
  for (int k = 0; k < n; ++k) {
    const double cdf = 1 - std::exp2(-std::pow(f[static_cast<std::size_t>(k)], m));
    d = std::max({d, std::abs(cdf - double(k) / n), std::abs(cdf - double(k + 1) / n)});
  }
  MESSAGE("KS distance ", d, " (critical ", 1.95 / std::sqrt(n), ")");
  CHECK(d < 1.95 / std::sqrt(double(n)));
}

TEST_CASE("strength scatter: a pulled pair breaks at its own factor times F_n,c") {
  auto p = undamped();
  p.weibull_modulus = 3;
  const SpringBond model(p);
  SpringPair pair(model);
  const double w = pair.scene.state[foreign::kStrengthFactor];
  CHECK(w == foreign::strength_factor(3, 0, 1, 0));
  const int n = 4000;
  const double h = 3 * p.normal_strength / p.normal_stiffness / n;
  int t = 0;
  for (int s = 1; s <= n && !t; ++s) {
    pair.place(s * h);
    pair.compute(model);
    if (pair.broken()) t = s;
  }
  REQUIRE(t > 0);
  CHECK(p.normal_stiffness * (t - 1) * h < w * p.normal_strength);
  CHECK(p.normal_stiffness * t * h >= w * p.normal_strength);
}

TEST_CASE("softening: F = k_n dx (1 - (dx / dx0 - 1) / s) past the peak, broken at (1 + s) dx0, no healing") {
  auto p = undamped();
  p.softening_ratio = 0.5;
  const SpringBond model(p);
  SpringPair pair(model);
  const double k = p.normal_stiffness, dx0 = p.normal_strength / k, s = p.softening_ratio;
  const int n = 3000;
  const double h = 2 * dx0 / n;  // dx0 and (1 + s) dx0 are grid points 1500 and 2250
  double largest_error = 0;
  int broke = 0;
  for (int t = 1; t <= n && !broke; ++t) {
    const double dx = t * h;
    pair.place(dx);
    pair.compute(model);
    if (pair.broken()) {
      broke = t;
      break;
    }
    const double expected = dx <= dx0 ? k * dx : k * dx * (1 - (dx / dx0 - 1) / s);
    largest_error = std::max(largest_error, std::abs(pair.force_on_first().x() - expected) / p.normal_strength);
  }
  MESSAGE("largest deviation ", largest_error, " of F_n,c");
  CHECK(largest_error < 1e-9);  // the load ratio dx / dx0 is computed from r - r0: ~1e-12 relative
  CHECK(std::abs(broke - 2250) <= 1);

  // Unloading after the peak keeps the damage: at dx0 / 2 the force is the damaged secant's.
  SpringPair other(model);
  other.place(1.25 * dx0);
  other.compute(model);
  other.place(0.5 * dx0);
  other.compute(model);
  const double damage_factor = 1 - 0.25 / s;
  CHECK(other.force_on_first().x() == doctest::Approx(damage_factor * k * 0.5 * dx0).epsilon(1e-9));
  CHECK(other.scene.energy[0] == doctest::Approx(damage_factor * 0.5 * k * 0.25 * dx0 * dx0).epsilon(1e-9).scale(0));
}

TEST_CASE("compression stiffening: ratio x k_n while shortened, k_n while stretched") {
  auto p = undamped();
  p.compression_ratio = 2.5;
  const SpringBond model(p);
  SpringPair pair(model);
  const double dx = 2e-5;
  pair.place(-dx);
  pair.compute(model);
  const double compressed = pair.force_on_first().x();
  pair.place(dx);
  pair.compute(model);
  const double stretched = pair.force_on_first().x();
  CHECK(compressed == doctest::Approx(-2.5 * p.normal_stiffness * dx).epsilon(1e-9));
  CHECK(stretched == doctest::Approx(p.normal_stiffness * dx).epsilon(1e-9));
}

TEST_CASE("subcritical damage: held at load ratio c a bond fails after t_0 / c^n") {
  auto p = undamped();
  p.fatigue_time = 0.5;
  p.fatigue_exponent = 10;
  const SpringBond model(p);
  SpringPair pair(model);
  pair.scene.dt = 1e-3;
  const double c = 0.8;
  pair.place(c * p.normal_strength / p.normal_stiffness);
  const double steps = p.fatigue_time / std::pow(c, p.fatigue_exponent) / pair.scene.dt;  // 4657 steps
  int failed_at = 0;
  for (int t = 1; t <= 10000 && !failed_at; ++t) {
    pair.compute(model);
    if (pair.broken()) failed_at = t;
  }
  MESSAGE("failed at step ", failed_at, " of ", steps);
  CHECK(std::abs(failed_at - steps) <= 1);
}

TEST_CASE("subcritical damage: pulled 5x faster, the strength grows as 5^(1 / (n + 1))") {
  auto p = undamped();
  p.fatigue_time = 2e-4;
  p.fatigue_exponent = 16;
  const SpringBond model(p);
  // Ramp the stretch at a rate in units of the critical stretch per second; the load ratio at failure.
  auto strength = [&](double rate) {
    SpringPair pair(model);
    pair.scene.dt = 1e-6;
    const double critical = p.normal_strength / p.normal_stiffness;
    for (int t = 1; t < 10000000; ++t) {
      pair.place(rate * t * pair.scene.dt * critical);
      pair.compute(model);
      if (pair.broken()) return rate * t * pair.scene.dt;
    }
    return 0.0;
  };
  const double slow = strength(20), fast = strength(100);
  // Ramp c = r t: D = r^n t^(n+1) / ((n + 1) t_0) = 1 at c = ((n + 1) t_0 r)^(1 / (n + 1)) below 1.
  MESSAGE("load ratio at failure ", slow, " at 20/s, ", fast, " at 100/s");
  CHECK(slow == doctest::Approx(std::pow(17 * 2e-4 * 20, 1.0 / 17)).epsilon(1e-3).scale(0));
  CHECK(fast / slow == doctest::Approx(std::pow(5.0, 1.0 / 17)).epsilon(1e-3));
}

TEST_CASE("cohesion: a failed bond pulls with F_coh up to the range, then breaks") {
  auto p = undamped();
  p.cohesion_force = 0.2;
  p.cohesion_range = 1e-4;
  const SpringBond model(p);
  SpringPair pair(model);
  const double critical = p.normal_strength / p.normal_stiffness;
  pair.place(1.01 * critical);  // past the strength: fails into its pull
  pair.compute(model);
  CHECK_FALSE(pair.broken());
  CHECK(pair.force_on_first().x() == doctest::Approx(p.cohesion_force).epsilon(1e-12));
  CHECK(pair.force_on_first().y() == 0.0);
  pair.place(-0.5 * critical);  // pushed together: the pull stays, compression is the contact's
  pair.compute(model);
  CHECK(pair.force_on_first().x() == doctest::Approx(p.cohesion_force).epsilon(1e-12));
  pair.place(0.99 * p.cohesion_range);
  pair.compute(model);
  CHECK_FALSE(pair.broken());
  pair.place(1.01 * p.cohesion_range);
  pair.compute(model);
  CHECK(pair.broken());
  CHECK(pair.force_on_first().norm() == 0.0);
}

// Through the plugin file: the schema's neutral value of each effect, set explicitly against the
// plain law (the defaults), on random stretched, sheared, bent, twisted, moving pairs, some past
// their strength and some listed the other way round: every output bit-identical. And a size
// off neutral must change something, or this comparison could not fail.
TEST_CASE("each effect at its declared neutral value changes nothing, bit for bit") {
  PluginHost host;
  host.load_file(FOREIGN_PLUGIN_FILE);
  const PluginInfo& info = host.find(PluginKind::Bond, "foreign_spring_bond").info;
  const std::map<std::string, double> off_neutral{
      {"weibull_modulus", 3.0}, {"softening_ratio", 0.5}, {"compression_ratio", 2.0}, {"fatigue_time", 1e-9},
      {"cohesion_force", 0.1}};
  const auto plain = host.make_bond("foreign_spring_bond", host.params(PluginKind::Bond, "foreign_spring_bond", {}));
  // Bonds are recorded in the undeformed pairs, then every particle is moved, turned and set moving.
  auto bonded = [](const BondModel& model) {
    auto s = test::random_pairs<test::HandBonds>(2000, 21, {.swap_ids_every_seventh = true});
    s.dt = 1e-6;  // subcritical damage grows by dt c^n / t_0
    s.initialize(model);
    test::deform(s, 4, 0.08, 1.0);
    s.compute(model);
    return s;
  };
  const auto base = bonded(*plain);
  const auto broken = std::count(base.broken.begin(), base.broken.end(), std::uint8_t{1});
  MESSAGE(broken, " of 2000 bonds past their strength");
  CHECK(broken > 100);
  CHECK(broken < 1900);
  for (const auto& [name, size] : off_neutral) {
    const ParamSpec* spec = nullptr;
    for (const auto& s : info.params)
      if (s.name == name) spec = &s;
    REQUIRE(spec);
    REQUIRE(spec->neutral.has_value());
    const auto neutral = host.make_bond("foreign_spring_bond",
                                        host.params(PluginKind::Bond, "foreign_spring_bond", {{name, *spec->neutral}}));
    const auto s = bonded(*neutral);
    test::check_same_outputs(base, s);
    CHECK(s.state == base.state);

    const auto on = host.make_bond("foreign_spring_bond", host.params(PluginKind::Bond, "foreign_spring_bond", {{name, size}}));
    const auto t = bonded(*on);
    bool differs = false;
    for (std::size_t k = 0; k < t.i.size(); ++k)
      differs = differs || t.broken[k] != base.broken[k] || !test::same_bits(t.force[k], base.force[k]);
    CHECK_MESSAGE(differs, name, " = ", size, " changed nothing");
  }
}

}  // namespace shard::foreign_test
