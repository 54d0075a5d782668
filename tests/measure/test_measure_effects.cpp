// The candidate-effect library (effects.toml) and the linearised joint refit of base parameters
// and effects.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "shard/measure/diagnosis.hpp"
#include "shard/measure/diagnosis_step.hpp"
#include "shard/measure/effect_library.hpp"

using namespace shard::measure;
namespace fs = std::filesystem;

namespace {

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("shard_effects_" + name);
  std::ofstream(p) << text;
  return p;
}

}  // namespace

TEST_CASE("the shipped library parses and every effect switches something on") {
  // Sizes by rule resolved at the tiny beam's scales (10 ms to the peak, 2.5 N at 1 mm).
  TestScales tiny;
  tiny.time_to_peak = 0.01, tiny.peak_force = 2.5, tiny.peak_displacement = 1e-3, tiny.secant_compliance = 4e-4;
  const auto lib =
      with_test_plausible(read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml"), tiny);
  CHECK(lib.size() >= 6);
  for (const auto& e : lib) {
    CHECK(e.plausible != e.neutral);
    if (e.post_processing()) {
      CHECK(e.overrides(e.plausible).empty());
    } else {
      const auto o = e.overrides(e.plausible);
      REQUIRE(!o.empty());
      CHECK(o.back().rfind(e.parameter + "=", 0) == 0);
    }
  }
}

TEST_CASE("an effect's value stays inside its physical range, also where a linear step overshoots") {
  // Support friction from the grains' 0.67 (neutral) to the library's trial 0.1 (lubricated rollers):
  // a joint linear refit can ask for 1.29 trial steps, a friction of -0.065, which the scene
  // refuses; the value stops at the physical bound 0, 0.67 / 0.57 trial steps from neutral.
  const auto lib = read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
  const auto friction = select_effects(lib, {"support_friction"}).front();
  CHECK(friction.neutral == 0.67);  // the grains' friction of the scenes' Table I
  CHECK(friction.scale_max() == doctest::Approx(0.67 / 0.57));
  CHECK(friction.value_at(1.0) == doctest::Approx(0.1));
  CHECK(friction.value_at(1.29) == 0.0);
  CHECK(friction.value_at(friction.scale_max()) >= 0.0);  // no rounding past the bound
  const auto weibull = select_effects(lib, {"weibull_strength"}).front();
  CHECK(weibull.value_at(-0.5) == 0.0);
  CHECK(weibull.value_at(2.0) == doctest::Approx(8.0));
}

TEST_CASE("a refit's step keeps the side the data ask for when the effect's range reaches both sides") {
  // The supports' friction moves both ways from the grains' 0.67 (range 0-1.3, trial 0.1): data
  // that ask for rougher supports (scale -0.95: friction 1.21) are refit there, within 0.05-3.9
  // trial sizes of neutral and the range. The Weibull modulus has one side (min 0 = neutral): a
  // negative ask stays a small step on its trial's side.
  const auto lib = read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
  const auto friction = select_effects(lib, {"support_friction"}).front();
  const auto weibull = select_effects(lib, {"weibull_strength"}).front();
  CHECK(clamp_effect_scale(friction, -0.95) == doctest::Approx(-0.95));
  CHECK(friction.value_at(clamp_effect_scale(friction, -0.95)) == doctest::Approx(1.2115));
  CHECK(clamp_effect_scale(friction, -0.01) == doctest::Approx(-0.05));
  CHECK(friction.value_at(clamp_effect_scale(friction, -10)) == doctest::Approx(1.3));  // the range's max
  CHECK(clamp_effect_scale(friction, 0.5) == doctest::Approx(0.5));
  CHECK(clamp_effect_scale(weibull, -0.5) == doctest::Approx(0.05));
  CHECK(clamp_effect_scale(weibull, 9.0) == doctest::Approx(3.9));
}

TEST_CASE("value_format puts the scalar into a vector-valued scene key") {
  const auto lib = read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
  const auto weight = select_effects(lib, {"self_weight"});
  REQUIRE(weight.size() == 1);
  CHECK(weight[0].overrides(-9.81).back() == "simulation.gravity=[0.0, 0.0, -9.81]");
  CHECK(weight[0].overrides(0).back() == "simulation.gravity=[0.0, 0.0, 0]");
  const auto two = write_file("fmt.toml", "[[effect]]\nname = \"a\"\nparameter = \"simulation.gravity\"\n"
                                          "value_format = \"[{}, {}, 0]\"\nneutral = 0\nplausible = 1\n");
  CHECK_THROWS_WITH_AS(read_effect_library(two), doctest::Contains(":4:"), std::runtime_error);
  const auto none = write_file("nofmt.toml", "[[effect]]\nname = \"a\"\nparameter = \"simulation.gravity\"\n"
                                             "value_format = \"[0, 0, -1]\"\nneutral = 0\nplausible = 1\n");
  CHECK_THROWS_WITH_AS(read_effect_library(none), doctest::Contains("one {} where the value goes"), std::runtime_error);
}

TEST_CASE("a size is printed with its unit, and a dimensionless ratio with none") {
  const auto lib = read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
  const auto picked = select_effects(lib, {"support_friction", "machine_compliance"});
  REQUIRE(picked.size() == 2);
  const CandidateEffect& ratio = picked[0].unit == "1" ? picked[0] : picked[1];
  const CandidateEffect& compliance = picked[0].unit == "1" ? picked[1] : picked[0];
  CHECK(ratio.sized(2) == "2");
  CHECK(compliance.sized(4.87e-5) == "4.87e-05 m/N");
  CHECK(compliance.unit_suffix() == " m/N");
}

TEST_CASE("effects on a plugin another effect switches away from are not combined") {
  auto effect_on = [](const std::string& parameter, const std::string& plugin_switch = "") {
    CandidateEffect e;
    e.name = parameter;
    e.parameter = parameter;
    if (!plugin_switch.empty()) e.set = {plugin_switch};
    return e;
  };
  const CandidateEffect asymmetry = effect_on("bond.compression_stiffness_ratio");
  const CandidateEffect crushing = effect_on("bond.crushing_ratio", "bond.plugin=crushing_bond");
  const CandidateEffect friction = effect_on("material_pair.beam.support.friction");
  const CandidateEffect compliance = effect_on(kMachineCompliance);
  const CandidateEffect crushing_strength = effect_on("bond.crushing_strength", "bond.plugin=crushing_bond");
  const CandidateEffect other_law = effect_on("bond.other", "bond.plugin=other_bond");
  CHECK(crushing.plugin_set_for("bond") == "crushing_bond");
  CHECK(crushing.plugin_set_for("contact").empty());
  CHECK(effect_on("bond.crushing_ratio", "bond.plugin=\"crushing_bond\"").plugin_set_for("bond") == "crushing_bond");
  CHECK_FALSE(combinable(crushing, asymmetry));  // the crushing law has no beam bond's ratio
  CHECK_FALSE(combinable(asymmetry, crushing));
  CHECK_FALSE(combinable(crushing, other_law));  // one section, two plugins
  CHECK(combinable(crushing, crushing_strength));  // both on the crushing law
  CHECK(combinable(crushing, friction));  // another section
  CHECK(combinable(crushing, compliance));  // not a scene parameter
  CHECK(combinable(asymmetry, friction));
}

TEST_CASE("a rate effect on data that already have two rates asks for rates farther apart, not a second rate") {
  const auto lib = read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
  const auto picked = select_effects(lib, {"bond_viscosity", "bond_softening"});
  REQUIRE(picked.size() == 2);
  const CandidateEffect& rate = picked[0].rates_needed > 1 ? picked[0] : picked[1];
  const CandidateEffect& softening = picked[0].rates_needed > 1 ? picked[1] : picked[0];
  REQUIRE(rate.rates_needed == 2);
  CHECK(rate.separating_measurement({1, 1}) == rate.separated_by);
  const std::string two = rate.separating_measurement({2, 1});
  CHECK(two.find("farther apart than these 2") != std::string::npos);
  CHECK(two.find(rate.separated_by) == std::string::npos);
  CHECK(softening.separating_measurement({1, 1}) == softening.separated_by);
  CHECK(softening.separating_measurement({3, 1}) == softening.separated_by);
}

TEST_CASE("library errors name the file, line and the valid keys") {
  const auto p = write_file("bad.toml", "[[effect]]\nname = \"a\"\nparameter = \"bond.x\"\nneutral = 0\nplausibel = 1\n");
  try {
    read_effect_library(p);
    FAIL("accepted an unknown key");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK(what.find(":5:") != std::string::npos);
    CHECK(what.find("plausibel") != std::string::npos);
    CHECK(what.find("plausible") != std::string::npos);
  }
  const auto same = write_file("same.toml", "[[effect]]\nname = \"a\"\nparameter = \"bond.x\"\nneutral = 1\nplausible = 1\n");
  CHECK_THROWS_WITH_AS(read_effect_library(same), doctest::Contains("plausible equals neutral"), std::runtime_error);
  const std::string effect = "[[effect]]\nname = \"a\"\nparameter = \"bond.x\"\nneutral = 0\nplausible = 1\n";
  const auto twice = write_file("twice.toml", effect + effect);
  CHECK_THROWS_WITH_AS(read_effect_library(twice), doctest::Contains("twice.toml:7:8: effect name 'a' is used twice"),
                       std::runtime_error);
  const auto lib = read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
  CHECK_THROWS_WITH_AS(select_effects(lib, {"gravitee"}), doctest::Contains("machine_compliance"), std::runtime_error);
}

TEST_CASE("linear refit recovers base steps and effect sizes of an exactly linear residual") {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0, 1);
  const std::size_t m = 11;
  std::vector<std::vector<double>> J(2, std::vector<double>(m));
  EffectSignature s{"e", 1.0, std::vector<double>(m)};
  for (std::size_t i = 0; i < m; ++i) J[0][i] = g(rng), J[1][i] = g(rng), s.signature[i] = g(rng);
  // r0 = -(J dtheta + a s) with dtheta = (0.1, -0.2), a = 0.7: the refit must undo it exactly.
  std::vector<double> r0(m);
  for (std::size_t i = 0; i < m; ++i) r0[i] = -(0.1 * J[0][i] - 0.2 * J[1][i] + 0.7 * s.signature[i]);
  const LinearRefit with = linear_refit(r0, J, {s});
  CHECK(with.base_step[0] == doctest::Approx(0.1).epsilon(1e-9));
  CHECK(with.base_step[1] == doctest::Approx(-0.2).epsilon(1e-9));
  CHECK(with.effect_scale[0] == doctest::Approx(0.7).epsilon(1e-9));
  CHECK(with.chi_square < 1e-20);
  // Without the effect the base parameters leave exactly the part of a s outside their span.
  const LinearRefit without = linear_refit(r0, J, {});
  CHECK(without.chi_square > 1e-3);
  const Diagnosis d = diagnose(std::vector<std::string>(m, "c"), r0, J, {s});
  CHECK(without.chi_square == doctest::Approx(d.chi_square_unabsorbed).epsilon(1e-9));
}

TEST_CASE("a plausible size scaled from the test: a tenth of the time to peak, a fraction of the compliance") {
  const auto file = write_file("rule.toml", R"(
[[effect]]
name = "bond_viscosity"
parameter = "bond.viscosity_time"
unit = "s"
neutral = 0.0
min = 0.0
plausible_from = "time_to_peak"
plausible_factor = 0.1

[[effect]]
name = "machine_compliance"
parameter = "machine_compliance"
unit = "m/N"
neutral = 0.0
min = 0.0
plausible_from = "secant_compliance"
plausible_factor = 0.25
)");
  const auto lib = read_effect_library(file);
  // Two rates: peaks after 50 ms and 10 ms (0.02 and 0.1 m/s to a 1 mm peak at 2.5 N). The
  // viscosity is a tenth of the shorter time; the compliance a quarter of 1 mm / 2.5 N.
  auto specimen_peaking_at = [](double t_peak) {
    Specimen s;
    for (int i = 0; i <= 20; ++i) {
      const double t = t_peak * i / 10.0;
      s.curve.time.push_back(t);
      s.curve.displacement.push_back(1e-3 * i / 10.0);
      s.curve.force.push_back(i <= 10 ? 2.5 * i / 10.0 : 2.5 * (20 - i) / 10.0);
      s.curve.u_force.push_back(0.01);
      s.curve.u_displacement.push_back(1e-6);
    }
    return s;
  };
  const TestScales scales = test_scales({{specimen_peaking_at(0.05)}, {specimen_peaking_at(0.01)}});
  CHECK(scales.time_to_peak == doctest::Approx(0.01).scale(0));
  CHECK(scales.peak_force == doctest::Approx(2.5));
  CHECK(scales.secant_compliance == doctest::Approx(4e-4).scale(0));
  const auto resolved = with_test_plausible(lib, scales);
  CHECK(resolved[0].plausible == doctest::Approx(1e-3).scale(0));
  CHECK(resolved[1].plausible == doctest::Approx(1e-4).scale(0));
  // With the model run 5 x faster (--time-compression 5) its times are a fifth.
  CHECK(test_scales({{specimen_peaking_at(0.01)}}, 5).time_to_peak == doctest::Approx(0.002).scale(0));
  // A rule that puts the size outside the range is refused, naming the effect and the fix.
  auto negative = lib;
  negative[0].plausible_factor = -0.1;
  CHECK_THROWS_WITH_AS(with_test_plausible(negative, scales), doctest::Contains("effect 'bond_viscosity'"),
                       std::runtime_error);
  // An unknown scale, and a rule without its factor, are errors at the file's line.
  CHECK_THROWS_WITH_AS(read_effect_library(write_file("bad_rule.toml", "[[effect]]\nname = \"v\"\nparameter = \"a.b\"\n"
                                                                       "neutral = 0.0\nplausible_from = \"peak_time\"\n"
                                                                       "plausible_factor = 0.1\n")),
                       doctest::Contains("unknown plausible_from 'peak_time'"), std::runtime_error);
  CHECK_THROWS_WITH_AS(read_effect_library(write_file("half_rule.toml", "[[effect]]\nname = \"v\"\nparameter = \"a.b\"\n"
                                                                        "neutral = 0.0\nplausible_from = \"time_to_peak\"\n")),
                       doctest::Contains("go together"), std::runtime_error);
}
