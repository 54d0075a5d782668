// The candidate-effect library (effects.toml) and the linearised joint refit of base parameters
// and effects.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "shard/measure/diagnosis.hpp"
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
  const auto lib = read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
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
  // Hidden support friction 0.1 (the library's trial size, from the particles' 0.67): the joint
  // linear refit asked for 1.29 trial steps, wall_friction = -0.067, which hertz_mindlin_plus
  // refuses, so the refit failed and diagnose named weibull_strength instead.
  const auto lib = read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
  const auto friction = select_effects(lib, {"support_friction"}).front();
  CHECK(friction.scale_max() == doctest::Approx(0.67 / 0.57));
  CHECK(friction.value_at(1.0) == doctest::Approx(0.1));
  CHECK(friction.value_at(1.29) == 0.0);
  CHECK(friction.value_at(friction.scale_max()) >= 0.0);  // no rounding past the bound
  const auto weibull = select_effects(lib, {"weibull_strength"}).front();
  CHECK(weibull.value_at(-0.5) == 0.0);
  CHECK(weibull.value_at(2.0) == doctest::Approx(8.0));
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
