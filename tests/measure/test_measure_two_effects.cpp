// Two library effects hidden at once: a diagnosis that names one effect at a time
// must go on stepwise. Synthetic data on the tiny bending beam (packing seeds 1001-1003, the
// model's 1-3; the sensor model of test_measure_hidden_effects) with machine compliance 1e-4 m/N
// and bond softening ratio 3 hidden together; `shard diagnose --max-effects 2` must name both in
// its path, and what remains after the second must be noise. The shipped library: compliance
// trial 1.14e-4 m/N (a quarter of the base run's secant compliance), later refits converged.
// Four candidates (--only) keep the runs to ~60 (~2 min on two idle cores): the two hidden ones
// and the two that ranked above softening in its single-effect case (compression asymmetry) or
// absorb a lower peak (Weibull strength).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "shard/measure/diagnosis_step.hpp"
#include "shard_cli.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kWork = fs::current_path() / "measure_two_effects_work";
const std::string kScene = std::string(SHARD_SOURCE_DIR) + "/scenes/measurements/tiny_bending.toml";

void run_shard(const std::string& args) { shard_test::run_shard(args, kWork); }
using shard_test::read_text;

// diagnose.json's format version (single-set form) this test reads.
constexpr int kDiagnoseVersion = 1;

}  // namespace

TEST_CASE("a secant iteration takes a refit on where an effect's bent response stopped the linear one short") {
  // A residual model whose effect saturates with its size, r(d, a) = r0 + J d + t a^0.7 (a softening
  // ratio far beyond its trial bends the curve less than proportionally), with its exact fit at
  // d = 0.1, a = 2.4. The linear refit from the trial signature (a = 1: t) stops short; one secant
  // correction through its own "run" must land closer and leave a smaller chi^2.
  using namespace shard::measure;
  const std::vector<double> j{1, 1, 0, 0}, t{0, 1, 2, 1};
  auto model = [&](double d, double a) {
    ResidualVector r;
    r.names = {"regime:elastic", "regime:peak", "feature:post_peak_work", "feature:nonlinearity"};
    for (std::size_t i = 0; i < 4; ++i) r.values.push_back(-(0.1 * j[i] + std::pow(2.4, 0.7) * t[i]) + j[i] * d + t[i] * std::pow(a, 0.7));
    return r;
  };
  auto chi2 = [](const ResidualVector& r) {
    double x = 0;
    for (double v : r.values) x += v * v;
    return x;
  };
  const ResidualVector r0 = model(0, 0);
  EffectSignature sig{"saturating", 1.0, t};
  const LinearRefit linear = linear_refit(r0.values, {j}, {sig});
  const double a1 = linear.effect_scale.front(), d1 = linear.base_step.front();
  CHECK(a1 < 2.0);  // short of 2.4
  const auto secant = shard::measure::secant_refit(r0, {j}, &sig, {d1, a1}, model(d1, a1));
  REQUIRE(secant.has_value());
  const double a2 = secant->effect_scale.front(), d2 = secant->base_step.front();
  CHECK(std::abs(a2 - 2.4) < 0.5 * std::abs(a1 - 2.4));
  CHECK(chi2(model(d2, a2)) < 0.5 * chi2(model(d1, a1)));
  // A run whose components differ from the linearisation's (a regime vanished) is not iterated.
  ResidualVector other = model(d1, a1);
  other.names[0] = "regime:toe";
  CHECK_FALSE(shard::measure::secant_refit(r0, {j}, &sig, {d1, a1}, other).has_value());
}

TEST_CASE("iterated to convergence, a refit no longer depends on the trial size its signature was taken at") {
  // A kept effect whose response is not linear in its size (a compliance C moves the curve's
  // regimes and features as (C / C0)^0.7 here), its exact fit at C = 2.4e-4 with a base step
  // d = 0.1. Signatures taken at two trial sizes, 1e-4 and 1.14e-4 (the library's fixed size and
  // the scene rule's on the tiny beam), give linear refits that land at different sizes; secant
  // iterations (what diagnose runs on a kept effect and on every refit of a later step, at most
  // --refit-iterations of them) carry both to the same size.
  using namespace shard::measure;
  const std::vector<double> j{1, 1, 0, 0}, t{0, 1, 2, 1};
  const double truth = 2.4e-4, c0 = 1e-4;
  auto response = [&](double c) { return std::pow(c / c0, 0.7); };
  auto model = [&](double d, double c) {
    ResidualVector r;
    r.names = {"regime:elastic", "regime:peak", "feature:post_peak_work", "feature:nonlinearity"};
    for (std::size_t i = 0; i < 4; ++i) r.values.push_back(-(0.1 * j[i] + response(truth) * t[i]) + j[i] * d + t[i] * response(c));
    return r;
  };
  const ResidualVector r0 = model(0, 0);
  auto refit_at = [&](double trial, int iterations) {
    EffectSignature sig{"compliance", trial, {}};
    for (double x : t) sig.signature.push_back(x * response(trial));
    LinearRefit lr = linear_refit(r0.values, {j}, {sig});
    for (int k = 0; k < iterations; ++k) {
      const double d = lr.base_step.front(), a = lr.effect_scale.front();
      const auto next = shard::measure::secant_refit(r0, {j}, &sig, {d, a}, model(d, a * trial));
      REQUIRE(next.has_value());
      lr = *next;
    }
    return lr.effect_scale.front() * trial;
  };
  const double linear_1 = refit_at(1e-4, 0), linear_2 = refit_at(1.14e-4, 0);
  // One step solves a f(T) = f(truth): C = truth^0.7 T^0.3, 23 % and 20 % short, 4 % apart.
  CHECK(linear_1 == doctest::Approx(std::pow(truth, 0.7) * std::pow(1e-4, 0.3)).scale(0));
  CHECK(linear_2 / linear_1 == doctest::Approx(std::pow(1.14, 0.3)));
  const double iterated_1 = refit_at(1e-4, 4), iterated_2 = refit_at(1.14e-4, 4);
  // Each secant step through the origin shrinks the log error by the response's 0.3 (= 1 - 0.7).
  CHECK(iterated_1 == doctest::Approx(truth).epsilon(0.01).scale(0));
  CHECK(iterated_2 == doctest::Approx(truth).epsilon(0.01).scale(0));
  CHECK(std::abs(iterated_1 - iterated_2) < 0.1 * std::abs(linear_1 - linear_2));
}

TEST_CASE("machine compliance and bond softening hidden at once: both named, one after the other") {
  const fs::path meas = kWork / "meas", out = kWork / "diag";
  run_shard("synth --scene " + kScene + " --work " + kWork.string() + " --out " + meas.string() +
        " --scatter 0.02 --force-noise 0.01 --force-offset 0.005 --displacement-step 1e-6 --machine-compliance 1e-4"
        " --set bond.softening_ratio=3");
  run_shard("diagnose " + meas.string() + " --scene " + kScene + " --work " + kWork.string() +
        " --param bond.youngs_modulus --param bond.critical_stress --only "
        "machine_compliance,bond_softening,compression_asymmetry,weibull_strength --refit 2 --max-effects 2 --out " +
        out.string());
  const nlohmann::json json = shard_test::read_document(out / "diagnose.json", kDiagnoseVersion);
  INFO(json.dump());
  // Measured (compliance trial 1.14e-4 m/N by the scene rule): compliance kept first (chi^2
  // 75.9 -> 29.1, 69 % of the excess, p after 1.4e-4; carried by a secant step to 6.47e-5 m/N),
  // softening named second on what compliance leaves (converged: 14.9 -> 2.0, p after 0.92;
  // Weibull 3.2 a rival). At step 1 the two refits nearly tie (29.1 and 28.0), so the order is not
  // asserted: the path must hold both, its first step must have left structure (why it went on)
  // and its last noise (the name's meaning).
  const std::string verdict = json.at("verdict");
  CHECK((verdict == "machine_compliance + bond_softening" || verdict == "bond_softening + machine_compliance"));
  const nlohmann::json& path = json.at("path");
  REQUIRE(path.size() == 2);
  const nlohmann::json& compliance = shard_test::element_with(path, "effect", "machine_compliance");
  const nlohmann::json& softening = shard_test::element_with(path, "effect", "bond_softening");
  const nlohmann::json &first = path.front(), &last = path.back();
  CHECK(first.at("p_after").get<double>() < 0.05);
  CHECK(first.at("named") == false);
  CHECK(last.at("p_after").get<double>() > 0.05);
  CHECK(last.at("named") == true);
  // Sizes: the order of each. Compliance within a factor 2 of the truth (measured 0.65 at step 1,
  // before softening is modelled: the single-effect band 2/3..3/2 widened for the second,
  // unmodelled effect); softening within 2/3..3/2 of the truth 3 as in the single-effect test
  // (measured 3.9, the refit's bound of 3.9 plausible sizes: the two trade off).
  const double c = compliance.at("value").get<double>() / 1e-4;
  CHECK(c > 0.5);
  CHECK(c < 2.0);
  const double s = softening.at("value").get<double>() / 3;
  CHECK(s > 2.0 / 3.0);
  CHECK(s < 1.5);
}

TEST_CASE("the same data with Welch scores on 8 model packings: compliance named, nothing wrong") {
  // Each component's variance comes from 3 specimens and 3 replicates: read as N(0, 1) its tails
  // are too heavy, and over ten draws of this truth the true model was rejected at p < 0.01 in 2
  // and a wrong effect (weibull_strength) named in 2. Read as Student t on its Welch-Satterthwaite
  // dof with 8 model packings, the ten draws gave machine_compliance in 8, nothing wrong
  // (docs/explanation/diagnosis.md, "From curves to residuals"). On this draw: machine_compliance alone.
  const fs::path meas = kWork / "meas2", out = kWork / "diag_welch8";
  run_shard("synth --scene " + kScene + " --work " + kWork.string() + " --out " + meas.string() +
            " --scatter 0.02 --force-noise 0.01 --force-offset 0.005 --displacement-step 1e-6 --machine-compliance 1e-4"
            " --set bond.softening_ratio=3");  // the data of the test above (same seeds), cached runs
  run_shard("diagnose " + meas.string() + " --scene " + kScene + " --work " + kWork.string() +
            " --param bond.youngs_modulus --param bond.critical_stress --only "
            "machine_compliance,bond_softening,compression_asymmetry,weibull_strength --refit 2 --max-effects 2 "
            "--seeds 8 --score-reference welch --out " + out.string());
  const nlohmann::json json = shard_test::read_document(out / "diagnose.json", kDiagnoseVersion);
  INFO(json.dump());
  const std::string verdict = json.at("verdict");
  CHECK(verdict.rfind("machine_compliance", 0) == 0);
  CHECK(verdict.find("weibull") == std::string::npos);
  CHECK(verdict.find("asymmetry") == std::string::npos);
  CHECK(read_text(out / "diagnose.md").find("Welch-Satterthwaite") != std::string::npos);
}
