// Each contact effect policy, named in `effects` with its parameter at the neutral value of its
// schema, must be the plain law: the shipped plugin files, random particle-particle and
// particle-wall contacts over 50 steps of history (sticking and sliding), forces, couples,
// energies and histories bit-identical.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "contact_batch.hpp"
#include "shard/measure/effect_library.hpp"
#include "shard/plugin_host.hpp"

namespace shard::effects_test {
namespace {

void check_same_bits(const ContactModel& base, const ContactModel& named) {
  REQUIRE(base.history_size() == named.history_size());
  CHECK(base.time_step_limit(0.35e-3, 3720).recommended == named.time_step_limit(0.35e-3, 3720).recommended);
  const std::size_t n = 1000;
  ContactScene a(n, base.history_size());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::size_t k = 0; k < n; ++k) {
    a.j[k] = k % 4 == 0 ? -1 - static_cast<Index>(k % 3) : 1;  // a quarter at walls
    a.r_eff[k] = 0.2e-3 * (1.5 + u(rng));
    a.m_eff[k] = 1e-6 * (1.5 + u(rng));
  }
  ContactScene b = a;
  std::size_t sliding = 0;
  for (int step = 0; step < 50; ++step) {
    for (std::size_t k = 0; k < n; ++k) {
      Vec3 nrm(u(rng), u(rng), u(rng));
      const Vec3 normal = (Vec3::UnitZ() + 0.05 * nrm).normalized();
      const double delta = 1e-6 * (1.2 + u(rng));
      const Vec3 velocity(0.05 * u(rng), 0.05 * u(rng), 0.01 * u(rng));
      a.normal[k] = b.normal[k] = normal;
      a.overlap[k] = b.overlap[k] = delta;
      a.velocity[k] = b.velocity[k] = velocity;
    }
    a.compute(base, 1e-6);
    b.compute(named, 1e-6);
    for (std::size_t k = 0; k < n; ++k) {
      CHECK(std::memcmp(a.force[k].data(), b.force[k].data(), 3 * sizeof(double)) == 0);
      CHECK(std::memcmp(a.couple[k].data(), b.couple[k].data(), 3 * sizeof(double)) == 0);
      CHECK(std::memcmp(&a.energy[k], &b.energy[k], sizeof(double)) == 0);
      const Vec3 f_t = a.force[k] - a.force[k].dot(a.normal[k]) * a.normal[k];
      const double f_n = a.force[k].dot(a.normal[k]);
      if (f_t.norm() >= 0.67 * f_n * (1 - 1e-12)) ++sliding;
    }
    CHECK(std::memcmp(a.history.data(), b.history.data(), a.history.size() * sizeof(double)) == 0);
  }
  MESSAGE(sliding, " of ", 50 * n, " contact evaluations at the Coulomb cap");
  CHECK(sliding > 1000);  // both branches compared
}

}  // namespace

TEST_CASE("each contact effect policy named at its schema's neutral value is bit-identical to the plain law") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_hertz_mindlin.so");
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_linear_spring.so");
  for (const std::string law : {"hertz_mindlin", "linear_spring"}) {
    CAPTURE(law);
    std::map<std::string, ParamValue> neutral;
    for (const auto& spec : host.find(PluginKind::Contact, law).info.params)
      if (spec.name == "support_friction_ratio" || spec.name == "cohesion_stress") {
        REQUIRE(spec.neutral.has_value());
        neutral[spec.name] = *spec.neutral;
      }
    CHECK(neutral.size() == (law == "hertz_mindlin" ? 2u : 1u));
    const auto base = host.make_contact(law, host.params(PluginKind::Contact, law, {}));
    const std::string all = law == "hertz_mindlin" ? "cohesion, support_friction" : "support_friction";
    for (const std::string& names : {std::string("support_friction"), all}) {
      CAPTURE(names);
      auto params = neutral;
      params["effects"] = names;
      check_same_bits(*base, *host.make_contact(law, host.params(PluginKind::Contact, law, params)));
    }
  }
}

TEST_CASE("an unknown effect name lists the law's policies") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_linear_spring.so");
  // linear_spring offers support_friction only: cohesion's area pi R* delta is the Hertz contact's.
  CHECK_THROWS_WITH(host.make_contact("linear_spring", host.params(PluginKind::Contact, "linear_spring",
                                                                   {{"effects", std::string("cohesion")}})),
                    doctest::Contains("valid: support_friction"));
}

// A neutral value is one the parameter can take: `shard diagnose` writes it into a scene (an
// infinite strength, say, would be refused by the parameter check, which wants finite values).
TEST_CASE("every shipped plugin's neutral values pass its own parameter check") {
  PluginHost host;
  host.load_directories({SHARD_BUILD_DIR "/plugins"});
  int checked = 0;
  for (const LoadedPlugin* plugin : host.plugins())
    for (const auto& spec : plugin->info.params) {
      if (!spec.neutral) continue;
      CAPTURE(plugin->info.name);
      CAPTURE(spec.name);
      const ParamValue value = spec.type == ParamType::Boolean ? ParamValue(*spec.neutral != 0) : ParamValue(*spec.neutral);
      CHECK_NOTHROW(host.params(plugin->info.kind, plugin->info.name, {{spec.name, value}}));
      ++checked;
    }
  CHECK(checked >= 12);  // beam_bond's, hertz_mindlin's and linear_spring's
}

// The effect library reads a plugin parameter's neutral value from the schema (it is declared
// once, there) and refuses an entry that contradicts it, naming the file, line and key.
TEST_CASE("the effect library's contact effects take the neutral values of hertz_mindlin's schema") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_hertz_mindlin.so");
  const auto& params = host.find(PluginKind::Contact, "hertz_mindlin").info.params;
  int contact_effects = 0;
  for (const auto& effect : measure::read_effect_library(SHARD_SOURCE_DIR "/scenes/measurements/effects.toml")) {
    if (effect.parameter.rfind("contact.", 0) != 0) continue;
    CAPTURE(effect.name);
    const auto spec = std::find_if(params.begin(), params.end(),
                                   [&](const ParamSpec& p) { return "contact." + p.name == effect.parameter; });
    REQUIRE(spec != params.end());
    REQUIRE(spec->neutral.has_value());
    CHECK(effect.neutral == *spec->neutral);
    CHECK(effect.set.empty());  // the parameter alone switches the policy on
    ++contact_effects;
  }
  CHECK(contact_effects == 1);  // contact_cohesion (support_friction is the supports' pair friction)

  const std::filesystem::path file = std::filesystem::path(SHARD_BUILD_DIR) / "tests/effects/contradicting_neutral.toml";
  std::ofstream(file) << "[[effect]]\nname = \"support_friction\"\nparameter = \"contact.support_friction_ratio\"\n"
                         "neutral = 0.67\nplausible = 0.1\n";
  CHECK_THROWS_WITH(measure::read_effect_library(file),
                    doctest::Contains("contradicting_neutral.toml:4:11: effect 'support_friction': neutral 0.67 "
                                      "contradicts the neutral value 1"));
  std::ofstream(file) << "[[effect]]\nname = \"compliance\"\nparameter = \"machine_compliance\"\nplausible = 1e-4\n";
  CHECK_THROWS_WITH(measure::read_effect_library(file), doctest::Contains("needs a neutral value"));
}

}  // namespace shard::effects_test
