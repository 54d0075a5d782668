// The diagnosis statistics in a linear world where the truth is known: residual = J dtheta +
// a s_true + N(0, 1) noise.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "shard/measure/diagnosis.hpp"
#include "shard/measure/statistics.hpp"

using namespace shard::measure;

namespace {

constexpr std::size_t kM = 11;  // five regimes + six curve features

std::vector<double> random_vector(std::mt19937_64& rng, double scale) {
  std::normal_distribution<double> g(0, scale);
  std::vector<double> v(kM);
  for (auto& x : v) x = g(rng);
  return v;
}

struct World {
  std::vector<std::string> names;
  std::vector<std::vector<double>> jacobian;
  std::vector<EffectSignature> effects;
};

World make_world(std::mt19937_64& rng) {
  World w;
  for (std::size_t i = 0; i < kM; ++i) w.names.push_back(std::string(1, static_cast<char>('a' + i)));
  w.jacobian = {random_vector(rng, 3), random_vector(rng, 3)};  // E_b, sigma_crit
  for (int e = 0; e < 4; ++e) w.effects.push_back({std::string("effect").append(1, static_cast<char>('0' + e)), 0.5, random_vector(rng, 3)});
  return w;
}

std::vector<double> residual(const World& w, std::mt19937_64& rng, int hidden, double amplitude) {
  auto r = random_vector(rng, 1);  // noise
  std::normal_distribution<double> g(0, 1);
  const double d0 = g(rng), d1 = g(rng);  // any base-parameter offset is absorbable
  for (std::size_t i = 0; i < kM; ++i) {
    r[i] += d0 * w.jacobian[0][i] + d1 * w.jacobian[1][i];
    if (hidden >= 0) r[i] += amplitude * w.effects[static_cast<std::size_t>(hidden)].signature[i];
  }
  return r;
}

}  // namespace

TEST_CASE("a hidden effect is ranked first and its size and sign are recovered") {
  std::mt19937_64 rng(42);
  int first = 0, trials = 50;
  double size_error = 0;
  for (int t = 0; t < trials; ++t) {
    const World w = make_world(rng);
    const int hidden = t % 4;
    const double amplitude = -2.0;  // the data have the effect at -2 x the trial size ...
    const Diagnosis d = diagnose(w.names, residual(w, rng, hidden, amplitude), w.jacobian, w.effects);
    // ... and the model lacks it, so the fit must add +2 x trial size = +1.0.
    if (d.ranking.front().name == w.effects[static_cast<std::size_t>(hidden)].name) {
      ++first;
      size_error = std::max(size_error, std::abs(d.ranking.front().size - 1.0));
      CHECK(d.verdict == w.effects[static_cast<std::size_t>(hidden)].name);
      CHECK(d.ranking.front().delta_aic < -10);
    }
  }
  // Signal |a s| ~ 2 x 3 x sqrt(11) = 20 against unit noise: misranking needs a near-collinear
  // random pair, rare in 11 dimensions.
  CHECK(first >= 47);
  // Size error ~ 1 / |t| / trial_size^-1 ~ 0.5 / 10: well under 0.3.
  CHECK(size_error < 0.3);
}

TEST_CASE("null case: adequate at the nominal rate") {
  std::mt19937_64 rng(3);
  int adequate = 0;
  const int trials = 400;
  for (int t = 0; t < trials; ++t) {
    const World w = make_world(rng);
    if (diagnose(w.names, residual(w, rng, -1, 0), w.jacobian, w.effects).verdict == "adequate") ++adequate;
  }
  // chi-square(m - p) test at 5 %: expect 95 % adequate; binomial sd 1.1 %, allow 4 sd.
  const double rate = adequate / static_cast<double>(trials);
  CHECK(rate > 0.95 - 0.044);
  CHECK(rate < 0.95 + 0.044);
}

TEST_CASE("a residual no effect can produce is unexplained; absorbed effects score zero") {
  std::mt19937_64 rng(9);
  World w = make_world(rng);
  // A residual orthogonal to every effect signature and to the Jacobian: only noise-free
  // structure outside the library.
  std::vector<double> r(kM, 0.0);
  r[0] = 1;
  r[1] = -1;
  std::vector<std::vector<double>> basis = w.jacobian;
  for (const auto& e : w.effects) basis.push_back(e.signature);
  // Gram-Schmidt r against the basis (6 vectors in 11 dimensions).
  std::vector<std::vector<double>> ortho;
  for (auto b : basis) {
    for (const auto& q : ortho) {
      double dot = 0;
      for (std::size_t i = 0; i < kM; ++i) dot += b[i] * q[i];
      for (std::size_t i = 0; i < kM; ++i) b[i] -= dot * q[i];
    }
    double n = 0;
    for (double x : b) n += x * x;
    for (auto& x : b) x /= std::sqrt(n);
    ortho.push_back(b);
  }
  for (const auto& q : ortho) {
    double dot = 0;
    for (std::size_t i = 0; i < kM; ++i) dot += r[i] * q[i];
    for (std::size_t i = 0; i < kM; ++i) r[i] -= dot * q[i];
  }
  for (auto& x : r) x *= 20;  // far beyond noise
  const Diagnosis d = diagnose(w.names, r, w.jacobian, w.effects);
  CHECK(d.verdict == "unexplained structured residual");
  CHECK(d.ranking.front().score < 1e-9 * d.chi_square_unabsorbed);

  // An "effect" that is a mix of the base parameters is absorbed entirely.
  EffectSignature absorbed{"stiffer bonds again", 1, {}};
  for (std::size_t i = 0; i < kM; ++i) absorbed.signature.push_back(2 * w.jacobian[0][i] - w.jacobian[1][i]);
  const Diagnosis d2 = diagnose(w.names, residual(w, rng, 0, -2), w.jacobian, {w.effects[0], absorbed});
  CHECK(d2.ranking.back().name == "stiffer bonds again");
  CHECK(d2.ranking.back().score == doctest::Approx(0).epsilon(1e-9));
}

TEST_CASE("collinear signatures are named as indistinguishable") {
  std::mt19937_64 rng(5);
  World w = make_world(rng);
  auto twin = w.effects[1];
  twin.name = "twin";
  for (std::size_t i = 0; i < kM; ++i) twin.signature[i] = -1.5 * twin.signature[i] + 0.3 * w.jacobian[0][i];
  w.effects.push_back(twin);
  const Diagnosis d = diagnose(w.names, residual(w, rng, 1, -2), w.jacobian, w.effects);
  REQUIRE(d.indistinguishable.size() == 1);
  CHECK(d.indistinguishable[0].first == "effect1");
  CHECK(d.indistinguishable[0].second == "twin");
  // The twin explains the residual equally well, with the opposite sign and 1 / 1.5 the size.
  CHECK(d.ranking[0].score == doctest::Approx(d.ranking[1].score).epsilon(1e-9));
}

TEST_CASE("an effect the data want reversed scores nothing when its range forbids it") {
  // Residual +2 s: the fit must add -2 x the trial (size -1.0), e.g. a negative compliance.
  // Two-sided it is found; with a >= 0 it scores 0.
  std::mt19937_64 rng(7);
  World w = make_world(rng);
  const auto r = residual(w, rng, 0, 2.0);  // the fit must add -2 x the trial size
  const Diagnosis free = diagnose(w.names, r, w.jacobian, w.effects);
  REQUIRE(free.ranking.front().name == "effect0");
  CHECK(free.ranking.front().size == doctest::Approx(-1.0).epsilon(0.3).scale(0));
  CHECK_FALSE(free.ranking.front().at_bound);

  w.effects[0].scale_min = 0;  // only >= neutral is physical
  const Diagnosis bounded = diagnose(w.names, r, w.jacobian, w.effects);
  for (const auto& s : bounded.ranking)
    if (s.name == "effect0") {
      CHECK(s.score == 0.0);
      CHECK(s.size == 0.0);
      CHECK(s.at_bound);
      CHECK(s.p_value == doctest::Approx(1.0));
    }
  CHECK(bounded.ranking.front().name != "effect0");

  // A bound the estimate stays inside changes nothing; one it crosses caps the size, and the
  // score is the drop at the cap: below the free LM, above zero.
  w.effects[0].scale_min = -10;
  const Diagnosis wide = diagnose(w.names, r, w.jacobian, w.effects);
  CHECK(wide.ranking.front().score == doctest::Approx(free.ranking.front().score).epsilon(1e-12));
  w.effects[0].scale_min = -1;  // half of the -2 the data need
  const Diagnosis capped = diagnose(w.names, r, w.jacobian, w.effects);
  for (const auto& s : capped.ranking)
    if (s.name == "effect0") {
      CHECK(s.at_bound);
      CHECK(s.size == doctest::Approx(-0.5));  // -1 x trial size 0.5
      CHECK(s.score > 0);
      CHECK(s.score < free.ranking.front().score);
    }
}

// Seeds s + u, s - u and s with u = lambda s average to s and move the residual by G (1 + lambda),
// G (1 - lambda) and G: a one-sided t of sqrt(3) / lambda on 2 degrees of freedom, whose upper
// tail is 1/2 - t / (2 sqrt(t^2 + 2)).
TEST_CASE("a signature the packing seeds do not resolve is ranked but decides nothing") {
  std::mt19937_64 rng(7);
  World w = make_world(rng);
  const std::vector<double> r = residual(w, rng, 0, -4.0);
  auto with_seeds = [&](double lambda) {
    World seeded = w;
    EffectSignature& e = seeded.effects[0];
    e.seed_signatures = {e.signature, e.signature, e.signature};
    for (std::size_t i = 0; i < kM; ++i) {
      e.seed_signatures[0][i] *= 1 + lambda;
      e.seed_signatures[1][i] *= 1 - lambda;
    }
    return diagnose(w.names, r, seeded.jacobian, seeded.effects);
  };
  auto entry = [](const Diagnosis& d, const std::string& name) {
    for (const auto& s : d.ranking)
      if (s.name == name) return s;
    FAIL("no ranking entry for " << name);
    return EffectScore{};
  };
  const std::string hidden = w.effects[0].name;
  REQUIRE(diagnose(w.names, r, w.jacobian, w.effects).verdict == hidden);  // without seeds it is named

  const Diagnosis agreeing = with_seeds(0.1);
  const double t_agree = std::sqrt(3.0) / 0.1;
  CHECK(entry(agreeing, hidden).seed_p == doctest::Approx(0.5 - t_agree / (2 * std::sqrt(t_agree * t_agree + 2))));
  CHECK(entry(agreeing, hidden).resolved);
  CHECK(agreeing.verdict == hidden);

  const Diagnosis scattered = with_seeds(2.0);
  const double t_scatter = std::sqrt(3.0) / 2.0;
  CHECK(entry(scattered, hidden).seed_p ==
        doctest::Approx(0.5 - t_scatter / (2 * std::sqrt(t_scatter * t_scatter + 2))));
  CHECK_FALSE(entry(scattered, hidden).resolved);
  CHECK(entry(scattered, hidden).score == doctest::Approx(entry(agreeing, hidden).score));  // still ranked by it
  CHECK(scattered.verdict != hidden);
}

// {1, 2, 3}: mean 2, sd 1, t = 2 sqrt(3) on 2 degrees of freedom.
TEST_CASE("mean_above_zero_p is the one-sided one-sample t-test") {
  const double t = 2 * std::sqrt(3.0);
  CHECK(mean_above_zero_p(std::vector<double>{1, 2, 3}) == doctest::Approx(0.5 - t / (2 * std::sqrt(t * t + 2))));
  CHECK(mean_above_zero_p(std::vector<double>{-1, -2, -3}) == 1);  // a mean below zero
  CHECK(mean_above_zero_p(std::vector<double>{2}) == 1);           // one value: no spread to test against
  CHECK(mean_above_zero_p(std::vector<double>{2, 2, 2}) == 0);     // every value alike and positive
}
