// Each effect policy of beam_bond, named in `effects` with its parameters at the neutral values
// its own schema declares, must run plain beam_bond's law: the shipped plugin file is loaded
// through the PluginHost and driven on the same random bonds (stretched, sheared, bent, twisted,
// moving, some past their strength, some listed the other way round); every force, torque,
// energy, break flag and break stress must be bit-identical, and the time step too.
#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "../bond/random_bonds.hpp"
#include "bond_batch.hpp"
#include "shard/measure/effect_library.hpp"
#include "shard/plugin_host.hpp"

namespace shard::effects_test {

using test::same_bits;

namespace {

// The policy names `effects` accepts, read from the schema's doc of `effects` would be circular:
// they are the four of docs/reference/effects.md, and an unknown one is refused (test below).
const std::vector<std::string> kPolicies{"weibull_strength", "softening", "viscosity", "compression_asymmetry"};

}  // namespace

TEST_CASE("each bond effect policy at its neutral values is bit-identical to plain beam_bond") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
  // Damping on, so the rate paths are compared too.
  const std::map<std::string, ParamValue> common{{"damping", 1e-3}, {"rotational_damping", 1.0}};
  std::map<std::string, ParamValue> neutral = common;
  int with_neutral = 0;
  for (const auto& spec : host.find(PluginKind::Bond, "beam_bond").info.params)
    if (spec.neutral && spec.name != "damping" && spec.name != "rotational_damping" && spec.name != "breakage") {
      neutral[spec.name] = *spec.neutral;
      ++with_neutral;
    }
  CHECK(with_neutral == 5);  // strength_weibull_modulus, strength_cv, softening_ratio, viscosity_time, compression_stiffness_ratio

  const auto base = host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", common));
  std::vector<std::string> selections = kPolicies;
  selections.push_back("weibull_strength, softening viscosity,compression_asymmetry");  // all four, mixed separators
  for (const std::string& selection : selections) {
    CAPTURE(selection);
    std::map<std::string, ParamValue> named = neutral;
    named["effects"] = selection;
    const auto law = host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", named));
    REQUIRE(law->state_size() > base->state_size());  // the effects variant is the one compared

    BondScene a = test::random_pairs<BondScene>(2000, 7);
    BondScene b = a;
    a.initialize(*base);
    b.initialize(*law);
    {
      BondBatch ba = a.batch(*base), bb = b.batch(*law);
      const TimeStepLimit la = base->time_step_limit(ba), lb = law->time_step_limit(bb);
      CHECK(same_bits(la.critical, lb.critical));
      CHECK(same_bits(la.recommended, lb.recommended));
    }
    std::size_t broken = 0, compared = 0;
    for (int step = 0; step < 4; ++step) {
      // Growing deformations: the last ones break a share of the bonds.
      test::deform(a, 100 + static_cast<std::uint64_t>(step), 0.01 * (step + 1), 0.5);
      test::deform(b, 100 + static_cast<std::uint64_t>(step), 0.01 * (step + 1), 0.5);
      a.compute(*base);
      b.compute(*law);
      compared += a.i.size();
      broken += test::check_same_outputs(a, b);
    }
    MESSAGE(selection, ": compared ", compared, " bond evaluations, ", broken, " of them breaks");
    // The comparison covered both intact and breaking bonds.
    CHECK(broken > 100);
    CHECK(broken < compared / 2);
  }
}

TEST_CASE("an unknown effect policy is refused with the valid names") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
  const auto params = host.params(PluginKind::Bond, "beam_bond", {{"effects", std::string("softening, sofening")}});
  std::string message;
  try {
    host.make_bond("beam_bond", params);
  } catch (const std::exception& e) {
    message = e.what();
  }
  CHECK(message.find("'sofening'") != std::string::npos);
  for (const auto& name : kPolicies) CHECK(message.find(name) != std::string::npos);
}

}  // namespace shard::effects_test

namespace shard::effects_test {

// The neutral value is declared in the policy's schema; the effect library repeats it for
// `shard diagnose`, and the two must not disagree (a trial run at the library's "neutral" would
// otherwise not be the base model).
TEST_CASE("the effect library's bond effects use the neutral values of beam_bond's schema") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
  const auto& params = host.find(PluginKind::Bond, "beam_bond").info.params;
  int bond_effects = 0;
  for (const auto& effect : measure::read_effect_library(SHARD_SOURCE_DIR "/scenes/measurements/effects.toml")) {
    if (effect.parameter.rfind("bond.", 0) != 0) continue;
    CAPTURE(effect.name);
    const std::string key = effect.parameter.substr(5);
    const auto spec = std::find_if(params.begin(), params.end(), [&](const ParamSpec& p) { return p.name == key; });
    REQUIRE(spec != params.end());
    REQUIRE(spec->neutral.has_value());
    CHECK(effect.neutral == *spec->neutral);
    CHECK(effect.set.empty());  // the parameter alone switches the policy on
    ++bond_effects;
  }
  CHECK(bond_effects == 4);
}

}  // namespace shard::effects_test
