// Features, regimes, residuals and verdict on curves whose answers are known in closed form.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "shard/measure/comparison.hpp"
#include "shard/measure/rate_comparison.hpp"
#include "shard/measure/report.hpp"
#include "shard/measure/statistics.hpp"

using namespace shard::measure;

namespace {

// Toe-free bilinear-with-softening curve: F = k w up to w_p, then a linear drop to zero at 2 w_p.
// `bend` adds pre-peak softening F = k w (1 - bend (w / w_p)^2).
Curve curve(double k, double w_p, double bend, double noise, std::mt19937& rng, double u_force) {
  std::normal_distribution<double> gauss(0, 1);
  Curve c;
  const int n = 400;
  for (int i = 0; i <= n; ++i) {
    const double w = 2.0 * w_p * i / n;
    const double rise = k * w * (1 - bend * (w / w_p) * (w / w_p));
    const double f_peak = k * w_p * (1 - bend);
    const double f = w <= w_p ? rise : f_peak * (2 - w / w_p);
    c.time.push_back(i * 0.01);
    c.displacement.push_back(w);
    c.force.push_back(f + noise * gauss(rng));
    c.u_displacement.push_back(1e-9);
    c.u_force.push_back(u_force);
  }
  return c;
}

Specimen specimen(Curve c) {
  Specimen s;
  s.curve = std::move(c);
  return s;
}

}  // namespace

TEST_CASE("features of a bilinear curve match their closed forms") {
  std::mt19937 rng(1);
  const double k = 2e5, w_p = 1e-3;  // 200 N/mm, F_max = 200 N
  const Curve c = curve(k, w_p, 0, 0, rng, 0.1);
  const FeatureValues f = curve_features(c);
  CHECK(*f[Feature::Stiffness] == doctest::Approx(k).epsilon(1e-9));
  CHECK(*f[Feature::PeakForce] == doctest::Approx(k * w_p));
  CHECK(*f[Feature::PeakDisplacement] == doctest::Approx(w_p).scale(0));
  // Triangles: 0.5 F_max w_p before and after the peak (the trapezoid rule is exact on lines).
  CHECK(*f[Feature::WorkToPeak] == doctest::Approx(0.5 * k * w_p * w_p).epsilon(1e-9));
  CHECK(*f[Feature::PostPeakWork] == doctest::Approx(0.5 * k * w_p * w_p).epsilon(1e-9));
  CHECK(std::abs(*f[Feature::Nonlinearity]) < 1e-9);
  // Softening before peak: the fit window (10-60 % of F_max) sees a slightly softened slope, so
  // compare the nonlinearity with the same construction done by hand on the exact curve.
  const Curve soft = curve(k, w_p, 0.2, 0, rng, 0.1);
  const FeatureValues fs = curve_features(soft);
  const ElasticFit fit = elastic_fit(soft);
  CHECK(*fs[Feature::Nonlinearity] == doctest::Approx(1 - 0.8 * k * w_p / (fit.stiffness * (w_p - fit.toe_offset))).scale(0));
  CHECK(*fs[Feature::Nonlinearity] > 0.1);  // 20 % softening at the peak, less in the fit window
}

TEST_CASE("fragment x50 is the mass-weighted median") {
  // Masses 1, 1, 8 at sizes 1, 2, 3: half the mass is reached at size 3.
  CHECK(fragment_x50({2, 1, 3}, {1, 1, 8}) == 3);
  CHECK(fragment_x50({1, 2, 3}, {5, 1, 1}) == 1);
}

TEST_CASE("chi-square survival and normal p-values at tabulated points") {
  CHECK(chi_square_survival(3.841459, 1) == doctest::Approx(0.05).epsilon(1e-5).scale(0));
  CHECK(chi_square_survival(18.307038, 10) == doctest::Approx(0.05).epsilon(1e-5).scale(0));
  CHECK(chi_square_survival(2.0, 2) == doctest::Approx(std::exp(-1.0)).epsilon(1e-12));
  CHECK(normal_two_sided(1.959964) == doctest::Approx(0.05).epsilon(1e-5).scale(0));
}

TEST_CASE("same truth, independent noise: adequate; stiffer model: elastic regime and stiffness fail") {
  std::mt19937 rng(7);
  const double k = 2e5, w_p = 1e-3, noise = 0.5;
  std::vector<Specimen> measured, same, stiffer;
  for (int i = 0; i < 3; ++i) measured.push_back(specimen(curve(k, w_p, 0.1, noise, rng, noise)));
  for (int i = 0; i < 3; ++i) same.push_back(specimen(curve(k, w_p, 0.1, noise, rng, noise)));
  for (int i = 0; i < 3; ++i) stiffer.push_back(specimen(curve(1.2 * k, w_p, 0.1, noise, rng, noise)));
  Metadata meta;
  meta.load_cell_uncertainty = noise;

  const Comparison ok = compare(measured, meta, same);
  CHECK(ok.adequate);
  CHECK(ok.verdict.rfind("adequate", 0) == 0);
  CHECK(ok.nrmse < 0.01);  // noise 0.5 N over a 180 N peak, averaged over three curves

  const Comparison bad = compare(measured, meta, stiffer);
  CHECK_FALSE(bad.adequate);
  const auto& elastic = bad.regimes[static_cast<std::size_t>(Regime::Elastic)];
  CHECK(elastic.beyond_noise);
  CHECK(elastic.relative_error == doctest::Approx(0.2).epsilon(0.05).scale(0));  // 20 % stiffer on the rise
  CHECK(elastic.mean_residual > 2);
  CHECK(bad.verdict.find("elastic") != std::string::npos);
  bool stiffness_flagged = false;
  for (const auto& f : bad.features)
    if (f.feature == Feature::Stiffness) {
      stiffness_flagged = f.beyond_noise;
      CHECK(f.relative_error == doctest::Approx(0.2).epsilon(0.02).scale(0));
    }
  CHECK(stiffness_flagged);
  // Regimes cover the grid without gaps, in order.
  std::size_t next = 0;
  for (const auto& g : bad.regimes) {
    CHECK(g.first == next);
    next = g.last;
  }
  CHECK(next == bad.xi.size());

  const auto md = comparison_markdown(bad);
  CHECK(md.find("| elastic |") != std::string::npos);
  // Through the text a strict parser reads: NaN scores (unjudged features) become null.
  const auto json = shard::io::Json::parse(comparison_json(bad).dump());
  CHECK(json["adequate"] == false);
  CHECK(json["features"].size() == bad.features.size());
  CHECK(json["regimes"].size() == kRegimeCount);

  const auto image = std::filesystem::temp_directory_path() / "shard_measure_compare.png";
  std::filesystem::remove(image);
  plot_comparison(bad, image, "stiffer model");
  CHECK(std::filesystem::file_size(image) > 1000);
}

namespace {

// A curve through the given (w, F) corners, sampled every `dw` by linear interpolation.
Curve polyline(const std::vector<std::pair<double, double>>& corners, double dw, double u_force) {
  Curve c;
  for (std::size_t k = 1; k < corners.size(); ++k) {
    const auto [w0, f0] = corners[k - 1];
    const auto [w1, f1] = corners[k];
    const int n = static_cast<int>(std::lround((w1 - w0) / dw));
    for (int i = (k == 1 ? 0 : 1); i <= n; ++i) {
      const double t = static_cast<double>(i) / n;
      c.time.push_back(static_cast<double>(c.time.size()) * 1e-3);
      c.displacement.push_back(w0 + t * (w1 - w0));
      c.force.push_back(f0 + t * (f1 - f0));
      c.u_displacement.push_back(1e-7);
      c.u_force.push_back(u_force);
    }
  }
  return c;
}

}  // namespace

TEST_CASE("fracture transients: crack initiation at the first significant drop, oscillations, failure point") {
  // Rise to 2.0 N at 1 mm, a first crack drops the load to 1.8 N (0.2 N: 8 % of F_max, above the
  // 2 % / 5 u_F threshold of 0.05 N), a second rise to the peak 2.5 N at 1.5 mm; after it the
  // load falls to 1.0 N, rings back up to 1.6 N and falls to 0: two reversals of dF/dw.
  const Curve c = polyline({{0, 0}, {1e-3, 2.0}, {1.05e-3, 1.8}, {1.5e-3, 2.5}, {1.7e-3, 1.0}, {1.8e-3, 1.6}, {2.2e-3, 0}},
                           1e-5, 0.01);
  CHECK(significant_drop(c) == doctest::Approx(0.05).scale(0));
  const FeatureValues f = curve_features(c);
  CHECK(*f[Feature::PeakForce] == doctest::Approx(2.5));
  CHECK(*f[Feature::InitiationForce] == doctest::Approx(2.0));
  CHECK(*f[Feature::Oscillations] == 2);
  // Half of F_max, 1.25 N, is first reached on the fall from 2.5 N at 1.5 mm to 1.0 N at 1.7 mm:
  // w = 1.5 + 0.2 x (2.5 - 1.25) / 1.5 mm.
  CHECK(*f[Feature::FailureDisplacement] == doctest::Approx(1.5e-3 + 0.2e-3 * 1.25 / 1.5).epsilon(1e-9));

  // A smooth rise and a monotone fall: initiation is the peak, no oscillation; a 0.04 N wiggle
  // (below the 0.05 N threshold) does not count.
  const Curve smooth = polyline({{0, 0}, {1e-3, 2.5}, {1.2e-3, 1.5}, {1.25e-3, 1.54}, {2e-3, 0.5}}, 1e-5, 0.01);
  const FeatureValues g = curve_features(smooth);
  CHECK(*g[Feature::InitiationForce] == doctest::Approx(2.5));
  CHECK(*g[Feature::Oscillations] == 0);
  // Damage that bends the curve before any drop: 2 N/mm to 2.0 N at 1 mm, then 1 N/mm to the peak.
  // The curve leaves the elastic line by more than the 0.052 N threshold (2 % of 2.6 N) past
  // w = 1.052 mm: initiation is the last point before, at 2.05 N; the overshoot is 27 %.
  const Curve bent = polyline({{0, 0}, {1e-3, 2.0}, {1.6e-3, 2.6}, {2e-3, 0}}, 1e-5, 0.01);
  const CrackInitiation at_bend = crack_initiation(bent);
  CHECK(at_bend.displacement == doctest::Approx(1.05e-3).epsilon(0.01).scale(0));
  CHECK(at_bend.force == doctest::Approx(2.05).epsilon(0.01));
  CHECK(*curve_features(bent)[Feature::InitiationForce] == doctest::Approx(at_bend.force));
  // The first drop of the cracked curve above: at 2.0 N and 1 mm, before its overshoot to 2.5 N.
  CHECK(crack_initiation(c).displacement == doctest::Approx(1e-3).scale(0));
  // Pins that meet the specimen at speed bounce in the seating toe: 0.2 N up, back to 0.05 N
  // (a fall of 0.15 N, beyond the 0.05 N threshold, at 8 % of F_max), then the cracked curve's
  // rise. The bounce is no crack: initiation stays at the first drop above the toe, 2.0 N at 1 mm.
  const Curve bounced = polyline({{0, 0}, {0.05e-3, 0.2}, {0.1e-3, 0.05}, {1e-3, 2.0}, {1.05e-3, 1.8}, {1.5e-3, 2.5},
                                  {1.7e-3, 1.0}, {2.2e-3, 0}},
                                 1e-5, 0.01);
  CHECK(crack_initiation(bounced).force == doctest::Approx(2.0));
  CHECK(crack_initiation(bounced).displacement == doctest::Approx(1e-3).scale(0));
  // A record cut while the load is still 60 % of F_max: the failure point is its end (a lower bound).
  const Curve cut = polyline({{0, 0}, {1e-3, 2.5}, {1.2e-3, 1.5}}, 1e-5, 0.01);
  CHECK(*curve_features(cut)[Feature::FailureDisplacement] == doctest::Approx(1.2e-3).scale(0));
}

TEST_CASE("crack initiation: a specimen ringing about its elastic line has not cracked") {
  // A beam loaded at speed: the rise 2 N/mm rings about its line by 0.08 N with a 0.4 mm period
  // (slope 2 - 0.08 x 2 pi / 0.4 = 1.26 N/mm > 0, so the force never falls), then the first crack
  // at 2.0 N and 1 mm drops it to 1.8 N, the overshoot peaks at 2.5 N at 1.5 mm, and the beam
  // fails. Each trough lies 0.08 N below the line, beyond the 0.05 N threshold (2 % of F_max), and
  // comes back above it: swings, not damage. Initiation is the crack, at 2.0 N and 1 mm.
  const double pi = std::acos(-1.0);
  std::vector<std::pair<double, double>> corners;
  for (int i = 0; i <= 100; ++i) {
    const double w = 1e-5 * i;
    corners.emplace_back(w, 2000.0 * w + 0.08 * std::sin(2 * pi * w / 0.4e-3));
  }
  for (auto corner : {std::pair{1.05e-3, 1.8}, {1.5e-3, 2.5}, {2.2e-3, 0.0}}) corners.push_back(corner);
  const Curve ringing = polyline(corners, 1e-5, 0.01);
  CHECK(significant_drop(ringing) == doctest::Approx(0.05).scale(0));
  const ElasticFit line = elastic_fit(ringing);
  double deepest = 0;  // the deepest trough below the line past the middle of the fit window
  for (std::size_t k = 0; k < ringing.size() && ringing.displacement[k] < 1e-3; ++k)
    if (ringing.force[k] > 0.35 * 2.5) deepest = std::max(deepest, line.force_at(ringing.displacement[k]) - ringing.force[k]);
  REQUIRE(deepest > significant_drop(ringing));
  const CrackInitiation at = crack_initiation(ringing);
  CHECK(at.force == doctest::Approx(2.0).epsilon(0.01));
  CHECK(at.displacement == doctest::Approx(1e-3).scale(0));
}

TEST_CASE("a model that fails later than the specimens is penalised by the failure point") {
  // The grid ends at the shortest measured curve; a model whose post-peak fall comes later shows
  // little there, but its failure displacement (half of F_max after the peak) is beyond noise,
  // judged with judge_fracture (reported, not judged, by default).
  std::mt19937 rng(3);
  std::normal_distribution<double> scatter(0, 0.02e-3);
  std::vector<Specimen> measured, late;
  for (int i = 0; i < 3; ++i) {
    const double e = scatter(rng);
    measured.push_back(specimen(polyline({{0, 0}, {1e-3, 2.5}, {1.4e-3 + e, 0.2}}, 1e-5, 0.01)));
    late.push_back(specimen(polyline({{0, 0}, {1e-3, 2.5}, {1.1e-3 + e, 2.3}, {4.8e-3 + e, 0.2}}, 1e-5, 0.01)));
  }
  Metadata meta;
  meta.load_cell_uncertainty = 0.01;
  CompareOptions fracture;
  fracture.judge_fracture = true;
  const Comparison c = compare(measured, meta, late, fracture);
  bool judged = false;
  for (const auto& f : c.features)
    if (f.feature == Feature::FailureDisplacement) {
      judged = f.judged;
      CHECK(f.beyond_noise);
      CHECK(f.simulated > 2 * f.measured);
    }
  CHECK(judged);
  bool in_vector = false;
  for (const auto& n : c.residual_vector().names) in_vector = in_vector || n == "feature:failure_displacement";
  CHECK(in_vector);
  // The oscillation count is never a score.
  for (const auto& n : c.residual_vector().names) CHECK(n != "feature:oscillations");
  // By default the failure point and the initiation force are reported but not judged.
  const Comparison plain = compare(measured, meta, late);
  for (const auto& n : plain.residual_vector().names) {
    CHECK(n != "feature:failure_displacement");
    CHECK(n != "feature:initiation_force");
  }
  bool reported = false;
  for (const auto& f : plain.features) reported = reported || (f.feature == Feature::FailureDisplacement && !f.judged);
  CHECK(reported);
}

TEST_CASE("a frozen simulated band: a model cannot lower its scores by scattering more") {
  // Same mean curves, 5 % too stiff; one model's replicates scatter by 10 % in force, the other's
  // not at all. Against its own band the scattering model scores lower; rescored with the tight
  // model's band, its residuals are the tight model's.
  std::mt19937 rng(11);
  const double k = 2e5, w_p = 1e-3, noise = 0.5;
  std::vector<Specimen> measured, tight, loose;
  for (int i = 0; i < 3; ++i) measured.push_back(specimen(curve(k, w_p, 0.1, noise, rng, noise)));
  for (int i = 0; i < 3; ++i) tight.push_back(specimen(curve(1.05 * k, w_p, 0.1, 0, rng, noise)));
  for (const double s : {0.9, 1.0, 1.1}) {
    Curve c = curve(1.05 * k, w_p, 0.1, 0, rng, noise);
    for (auto& f : c.force) f *= s;
    loose.push_back(specimen(c));
  }
  Metadata meta;
  meta.load_cell_uncertainty = noise;
  const Comparison t = compare(measured, meta, tight), l = compare(measured, meta, loose);
  auto chi2 = [](const Comparison& c) {
    double x = 0;
    for (double r : c.residual_vector().values) x += r * r;
    return x;
  };
  CHECK(chi2(l) < 0.1 * chi2(t));  // the scatter hides a 5 % error
  const Comparison frozen = with_simulated_band(l, t);
  CHECK(frozen.simulated.u == t.simulated.u);
  CHECK(frozen.nrmse == l.nrmse);
  // Same means (the loose replicates average to the tight curve), same band: same residuals.
  for (std::size_t k2 = 0; k2 < frozen.residual.size(); ++k2)
    CHECK(frozen.residual[k2] == doctest::Approx(t.residual[k2]).epsilon(1e-9));
  CHECK(chi2(frozen) == doctest::Approx(chi2(t)).epsilon(1e-6));
  // Other measurements (another grid) cannot lend their band.
  std::vector<Specimen> shorter;
  for (int i = 0; i < 3; ++i) shorter.push_back(specimen(curve(k, 0.8 * w_p, 0.1, noise, rng, noise)));
  CHECK_THROWS(with_simulated_band(l, compare(shorter, meta, tight)));
}

TEST_CASE("the likelihood's variance term charges a model for its wider band") {
  // One regime of two points with u_m = u_s = 1 (v = 2) against a reference with u_s = 0 (v = 1),
  // and one feature with u_m = 3, u_s = 4 (v = 25) against u_s = 0 (v = 9):
  // sum ln(v / v_ref) = ln 2 + ln(25 / 9).
  Comparison c;
  c.xi = {0, 1};
  c.measured.u = {1, 1};
  c.simulated.u = {1, 1};
  c.regimes[0].regime = Regime::Toe;
  c.regimes[0].first = 0;
  c.regimes[0].last = 2;
  for (std::size_t r = 1; r < kRegimeCount; ++r) c.regimes[r].first = c.regimes[r].last = 2;
  FeatureComparison f;
  f.feature = Feature::PeakForce;
  f.u_measured = 3;
  f.u_simulated = 4;
  f.score = 0.5;
  c.features.push_back(f);
  Comparison reference = c;
  reference.simulated.u = {0, 0};
  reference.features[0].u_simulated = 0;
  CHECK(log_variance_ratio(c, reference) == doctest::Approx(std::log(2.0) + std::log(25.0 / 9.0)));
  CHECK(log_variance_ratio(reference, reference) == 0);
  CHECK(log_variance_ratio(reference, c) == doctest::Approx(-std::log(2.0) - std::log(25.0 / 9.0)));
  // A feature that is not judged is not a component of the likelihood.
  c.features[0].judged = false;
  CHECK(log_variance_ratio(c, reference) == doctest::Approx(std::log(2.0)));
}

TEST_CASE("Welch-Satterthwaite degrees of freedom and the equivalent normal score at tabulated points") {
  // Two equal estimated variances of 3 samples each (dof 2): nu = (2v)^2 / (2 v^2 / 2) = 4.
  const VarianceTerm equal[] = {{1.0, 2.0}, {1.0, 2.0}};
  CHECK(satterthwaite_dof(equal, 0) == doctest::Approx(4.0).epsilon(1e-12));
  // A known variance (sensor noise) adds to the total but not to the sampling error: (1 + 1)^2 / (1 / 2) = 8.
  const VarianceTerm one[] = {{1.0, 2.0}};
  CHECK(satterthwaite_dof(one, 1.0) == doctest::Approx(8.0).epsilon(1e-12));
  // Welch's textbook case: s1^2/n1 = 2 on 4 dof, s2^2/n2 = 1 on 9 dof: 9 / (4/4 + 1/9) = 8.1.
  const VarianceTerm welch[] = {{2.0, 4.0}, {1.0, 9.0}};
  CHECK(satterthwaite_dof(welch, 0) == doctest::Approx(8.1).epsilon(1e-12));
  CHECK(std::isinf(satterthwaite_dof({}, 1.0)));
  // Student t quantiles: t(0.99; 3) = 4.540703 is the normal 0.99 quantile 2.326348;
  // t(0.025; 2) = -4.302653 the normal -1.959964; infinite dof leave the score alone.
  CHECK(equivalent_normal_score(4.540703, 3) == doctest::Approx(2.326348).epsilon(1e-5));
  CHECK(equivalent_normal_score(-4.302653, 2) == doctest::Approx(-1.959964).epsilon(1e-5));
  CHECK(equivalent_normal_score(1.5, std::numeric_limits<double>::infinity()) == 1.5);
  CHECK(equivalent_normal_score(0.0, 3) == doctest::Approx(0.0).epsilon(1e-12));
  // A large t on few dof stays finite and monotone: on 2 dof F(t) = 1/2 + t / (2 sqrt(2 + t^2)), so t = 40 has
  // the tail 3.1221e-4, z 3.42078.
  CHECK(equivalent_normal_score(40.0, 2) == doctest::Approx(3.420782).epsilon(1e-6));
  CHECK(equivalent_normal_score(400.0, 2) > equivalent_normal_score(40.0, 2));
}

TEST_CASE("three specimens against three replicates of the same truth: Welch scores keep their false-alarm rate") {
  // Specimen scatter (stiffness and strength 10 %) far above the load-cell noise: the peak-force
  // score's variance is estimated from 3 + 3 curves, so the raw score is t on ~4 dof. Read as
  // N(0, 1), |score| > 2.576 (p 0.01) happens in P(|t_4| > 2.576) = 6.2 % of the draws; the Welch
  // conversion brings it back to 1 %. 1000 draws: binomial sd 0.31 %, the bounds 3 sd around 1 %.
  std::mt19937 rng(2027);
  std::lognormal_distribution<double> scatter(0, 0.1);
  const double k = 2e5, w_p = 1e-3, noise = 0.01;
  Metadata meta;
  meta.load_cell_uncertainty = noise;
  CompareOptions welch;
  welch.score_reference = ScoreReference::Welch;
  const int draws = 1000;
  int alarms_normal = 0, alarms_welch = 0;
  double dof_sum = 0;
  auto peak_score = [](const Comparison& c) {
    for (const auto& f : c.features)
      if (f.feature == Feature::PeakForce) return std::pair{f.score, f.dof};
    return std::pair{0.0, 0.0};
  };
  for (int d = 0; d < draws; ++d) {
    std::vector<Specimen> measured, simulated;
    for (int i = 0; i < 3; ++i) measured.push_back(specimen(curve(k * scatter(rng), w_p * scatter(rng), 0.1, 0, rng, noise)));
    for (int i = 0; i < 3; ++i) simulated.push_back(specimen(curve(k * scatter(rng), w_p * scatter(rng), 0.1, 0, rng, 0)));
    const auto [raw, dof] = peak_score(compare(measured, meta, simulated));
    const auto [converted, dof_welch] = peak_score(compare(measured, meta, simulated, welch));
    CHECK(dof == doctest::Approx(dof_welch));
    CHECK(std::abs(converted) <= std::abs(raw) + 1e-12);  // a t tail is heavier: the normal score is smaller
    alarms_normal += std::abs(raw) > 2.5758;
    alarms_welch += std::abs(converted) > 2.5758;
    dof_sum += dof;
  }
  const double mean_dof = dof_sum / draws;
  CHECK(mean_dof > 2.0);
  CHECK(mean_dof < 4.0 + 1e-9);  // between min(n) - 1 and n_m + n_s - 2
  CHECK(alarms_normal > 40);     // expected ~62 (t on 2-4 dof)
  CHECK(alarms_welch >= 1);
  CHECK(alarms_welch <= 19);     // expected 10
  MESSAGE("false alarms at p 0.01 in ", draws, " draws: normal ", alarms_normal, ", welch ", alarms_welch,
          "; mean Satterthwaite dof ", mean_dof);
}

TEST_CASE("a model that is the truth has, on average, the NRMSE of the noise floor") {
  // noise_nrmse is the RMS of the combined band sqrt(u_m^2 + u_s^2) over F_max: the expected RMS of
  // the mean curves' difference when both sides draw from one truth (E[s^2] = sigma^2 on either
  // side). Specimen scatter 10 %, 3 curves a side; over 400 draws the mean squared NRMSE and the
  // mean squared floor agree within the draws' spread (a draw's NRMSE^2 has ~2 dof: the scatter
  // scales whole curves; measured 1.058).
  std::mt19937 rng(4242);
  std::lognormal_distribution<double> scatter(0, 0.1);
  const double k = 2e5, w_p = 1e-3;
  double nrmse2 = 0, floor2 = 0;
  const int draws = 400;
  for (int d = 0; d < draws; ++d) {
    std::vector<Specimen> measured, simulated;
    for (int i = 0; i < 3; ++i) measured.push_back(specimen(curve(k * scatter(rng), w_p * scatter(rng), 0.1, 0, rng, 0)));
    for (int i = 0; i < 3; ++i) simulated.push_back(specimen(curve(k * scatter(rng), w_p * scatter(rng), 0.1, 0, rng, 0)));
    const Comparison c = compare(measured, Metadata{}, simulated);
    nrmse2 += c.nrmse * c.nrmse;
    floor2 += c.noise_nrmse() * c.noise_nrmse();
  }
  const double ratio = nrmse2 / floor2;
  MESSAGE("mean NRMSE^2 / mean noise floor^2 over ", draws, " draws of one truth: ", ratio);
  CHECK(ratio > 0.8);
  CHECK(ratio < 1.25);
}

TEST_CASE("each packing seed's residual in the ensemble's band: the seeds' residuals average to the ensemble's") {
  // Regime means and feature scores are linear in the simulated mean once the band is fixed, so
  // what each seed alone contributes adds up to the ensemble's residual: a seed's residual is in
  // the units the diagnosis scores in.
  std::mt19937 rng(12);
  const double k = 2e5, w_p = 1e-3, noise = 0.5;
  std::vector<Specimen> measured, seeds;
  for (int i = 0; i < 3; ++i) measured.push_back(specimen(curve(k, w_p, 0.1, noise, rng, noise)));
  for (const double s : {0.92, 1.0, 1.07}) {
    Curve c = curve(1.05 * k, s * w_p, 0.1, 0, rng, noise);
    for (auto& f : c.force) f *= s;
    seeds.push_back(specimen(c));
  }
  Metadata meta;
  meta.load_cell_uncertainty = noise;
  RateComparison ensemble;
  ensemble.rates = {0.02};
  ensemble.at = {compare(measured, meta, seeds)};
  for (const auto& s : seeds) ensemble.seed_at.push_back({compare(measured, meta, {s})});
  const ResidualVector whole = ensemble.residual_vector();
  REQUIRE(whole.values.size() >= 5);
  std::size_t compared = 0;
  for (std::size_t i = 0; i < whole.names.size(); ++i) {
    double sum = 0;
    bool every_seed = true;
    for (std::size_t s = 0; s < seeds.size(); ++s) {
      const ResidualVector one = ensemble.seed_residual_vector(s, ensemble);
      const auto at = std::find(one.names.begin(), one.names.end(), whole.names[i]);
      if (at == one.names.end()) every_seed = false;
      else sum += one.values[static_cast<std::size_t>(at - one.names.begin())];
    }
    if (!every_seed) continue;
    CAPTURE(whole.names[i]);
    CHECK(sum / static_cast<double>(seeds.size()) == doctest::Approx(whole.values[i]).epsilon(1e-9).scale(1e-9));
    ++compared;
  }
  CHECK(compared >= 5);
}
