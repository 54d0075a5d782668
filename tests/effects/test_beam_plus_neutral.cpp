// At the neutral values of all four effects, beam_bond_plus must be beam_bond: both shipped
// plugin files are loaded through the PluginHost and driven on the same random bonds (stretched,
// sheared, bent, twisted, moving, some past their strength, some listed the other way round);
// every force, torque, energy, break flag and break stress must be bit-identical.
#include <doctest/doctest.h>

#include <map>

#include "../bond/random_bonds.hpp"
#include "bond_batch.hpp"
#include "shard/plugin_host.hpp"

namespace shard::effects_test {

using test::same_bits;

TEST_CASE("beam_bond_plus at neutral values is bit-identical to beam_bond") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond_plus.so");
  // Damping on, so the rate paths are compared too.
  const std::map<std::string, ParamValue> common{{"damping", 1e-3}, {"rotational_damping", 1.0}};
  std::map<std::string, ParamValue> neutral = common;
  const PluginInfo& plus_info = host.find(PluginKind::Bond, "beam_bond_plus").info;
  int effects = 0;
  for (const std::string name : {"strength_weibull_modulus", "softening_ratio", "viscosity_time",
                                 "compression_stiffness_ratio"}) {
    bool found = false;
    for (const auto& spec : plus_info.params)
      if (spec.name == name) {
        REQUIRE(spec.neutral.has_value());
        neutral[name] = *spec.neutral;
        found = true;
        ++effects;
      }
    CHECK(found);
  }
  CHECK(effects == 4);

  const auto base = host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", common));
  const auto plus = host.make_bond("beam_bond_plus", host.params(PluginKind::Bond, "beam_bond_plus", neutral));

  BondScene a = test::random_pairs<BondScene>(2000, 7);
  BondScene b = a;
  a.initialize(*base);
  b.initialize(*plus);
  {
    BondBatch ba = a.batch(*base), bb = b.batch(*plus);
    const TimeStepLimit la = base->time_step_limit(ba), lb = plus->time_step_limit(bb);
    CHECK(same_bits(la.critical, lb.critical));
    CHECK(same_bits(la.recommended, lb.recommended));
  }
  std::size_t broken = 0, compared = 0;
  for (int step = 0; step < 4; ++step) {
    // Growing deformations: the last ones break a share of the bonds.
    test::deform(a, 100 + static_cast<std::uint64_t>(step), 0.01 * (step + 1), 0.5);
    test::deform(b, 100 + static_cast<std::uint64_t>(step), 0.01 * (step + 1), 0.5);
    a.compute(*base);
    b.compute(*plus);
    compared += a.i.size();
    broken += test::check_same_outputs(a, b);
  }
  MESSAGE("compared ", compared, " bond evaluations, ", broken, " of them breaks");
  // The comparison covered both intact and breaking bonds.
  CHECK(broken > 100);
  CHECK(broken < compared / 2);
}

}  // namespace shard::effects_test
