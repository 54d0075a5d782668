// The host's composition of an out-of-tree bond effect onto beam_bond (shard/bond_effect.hpp,
// kernel/src/composed_bond.cpp), with the effect `shard new-plugin --effect` generates, filled in
// as test_damage (tests/plugin_api/CMakeLists.txt), and the hint for a retired plugin name.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>

#include "../bond/random_bonds.hpp"
#include "shard/plugin_host.hpp"

namespace shard {
namespace {

using test::same_bits;

// A step of 1e-6 s: the Maxwell arm of beam_bond's viscosity reads the step of the batch.
struct Pairs : test::HandBonds {
  Pairs() { dt = 1e-6; }
};

struct Host {
  PluginHost host;
  Host() {
    host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
    host.load_file(EFFECT_PLUGIN);
  }
  std::unique_ptr<BondModel> bond(const std::map<std::string, ParamValue>& values) const {
    return host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", values));
  }
};

// Table I beam with beam_bond's viscosity on: its law then rewrites its own state every step, so
// the comparisons below also check that the law's state survives the composition's repacking.
std::map<std::string, ParamValue> viscous_beam() {
  return {{"youngs_modulus", 12.8e6}, {"critical_stress", 0.24e6}, {"viscosity_time", 1e-5}};
}

}  // namespace

TEST_CASE("a retired plugin name gets the scene line that replaces it") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
  std::string message;
  try {
    host.find(PluginKind::Bond, "beam_bond_plus");
  } catch (const PluginError& e) {
    message = e.what();
  }
  CHECK(message.find("beam_bond_plus' was retired") != std::string::npos);
  CHECK(message.find("plugin = \"beam_bond\" with effects = ") != std::string::npos);
}

TEST_CASE("a bond effect's parameter joins its law's schema with its neutral value") {
  const Host h;
  const auto& beam = h.host.find(PluginKind::Bond, "beam_bond").info.params;
  const auto spec = std::find_if(beam.begin(), beam.end(),
                                 [](const ParamSpec& s) { return s.name == "test_damage_damage_per_strain"; });
  REQUIRE(spec != beam.end());
  CHECK(spec->neutral == 0.0);
  const auto effects = std::find_if(beam.begin(), beam.end(), [](const ParamSpec& s) { return s.name == "effects"; });
  REQUIRE(effects != beam.end());
  CHECK(effects->doc.find("out-of-tree effects loaded: test_damage") != std::string::npos);
  // beam_bond's own 9 doubles (l0, b1, b2): with the effect off the law runs alone.
  CHECK(h.bond({})->state_size() == 9);
  // Named, the effect's two doubles (l0, peak strain) follow the law's.
  CHECK(h.bond({{"effects", std::string("test_damage")}})->state_size() == 11);
  // Set away from neutral it is on without being named.
  CHECK(h.bond({{"test_damage_damage_per_strain", 3.0}})->state_size() == 11);
}

TEST_CASE("a bond effect whose parameter name is taken is refused, whichever loads first") {
  auto message_of = [](PluginHost& host, const char* file) {
    try {
      host.load_file(file);
    } catch (const PluginError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  {  // The law first: the effect's file is refused.
    PluginHost host;
    host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
    const std::string message = message_of(host, CLASH_PLUGIN);
    CHECK(message.find("bond effect 'clash' refused: its parameter 'critical_stress'") != std::string::npos);
    CHECK(host.bond_effects_for("beam_bond").empty());
  }
  {  // The effect first (a user's folder leads the search path): it is dropped, the law loads.
    PluginHost host;
    host.load_file(CLASH_PLUGIN);
    const std::string message = message_of(host, SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
    CHECK(message.find("bond effect 'clash' refused") != std::string::npos);
    CHECK(host.bond_effects_for("beam_bond").empty());
    const auto& params = host.find(PluginKind::Bond, "beam_bond").info.params;
    CHECK(std::count_if(params.begin(), params.end(), [](const ParamSpec& s) { return s.name == "critical_stress"; }) ==
          1);
  }
}

TEST_CASE("beam_bond's own policies and an out-of-tree effect are named in one effects key") {
  const Host h;
  auto values = viscous_beam();
  values["effects"] = std::string("viscosity, test_damage");
  CHECK(h.bond(values)->state_size() == 23 + 2);  // beam_bond's viscous state, then the effect's
  values["effects"] = std::string("viscosity, test_damag");
  std::string message;
  try {
    h.bond(values);
  } catch (const std::invalid_argument& e) {
    message = e.what();
  }
  CHECK(message.find("'test_damag'") != std::string::npos);
}

TEST_CASE("composed at its neutral value, the effect leaves beam_bond bit for bit") {
  const Host h;
  const auto plain = h.bond(viscous_beam());
  auto named = viscous_beam();
  named["effects"] = std::string("test_damage");
  const auto composed = h.bond(named);
  REQUIRE(composed->state_size() == plain->state_size() + 2);

  // 300 pairs: several of the composition's 64-bond blocks, the last one partial.
  Pairs a = test::random_pairs<Pairs>(300, 11);
  Pairs b = a;
  a.initialize(*plain);
  b.initialize(*composed);
  {
    BondBatch ba = a.batch(*plain), bb = b.batch(*composed);
    CHECK(same_bits(plain->time_step_limit(ba).recommended, composed->time_step_limit(bb).recommended));
  }
  std::size_t broken = 0, compared = 0;
  for (int step = 0; step < 4; ++step) {
    test::deform(a, 200 + static_cast<std::uint64_t>(step), 0.005 * (step + 1), 0.5);
    test::deform(b, 200 + static_cast<std::uint64_t>(step), 0.005 * (step + 1), 0.5);
    a.compute(*plain);
    b.compute(*composed);
    compared += a.i.size();
    broken += test::check_same_outputs(a, b);
    // The law's state, repacked around the effect's, is what the law alone keeps.
    const std::size_t law = plain->state_size(), stride = composed->state_size();
    bool same_state = true;
    for (std::size_t k = 0; k < a.i.size(); ++k)
      for (std::size_t s = 0; s < law; ++s) same_state = same_state && same_bits(a.state[k * law + s], b.state[k * stride + s]);
    CHECK(same_state);
  }
  MESSAGE("compared ", compared, " bond evaluations, ", broken, " of them breaks");
  CHECK(broken > 0);
  CHECK(broken < compared / 2);
}

TEST_CASE("composed on, the effect scales beam_bond's loads by 1 - c e_peak and breaks at 1") {
  const Host h;
  const double c = 300;  // damage per unit of peak tensile strain: broken at 0.33 %
  const auto plain = h.bond(viscous_beam());
  auto on = viscous_beam();
  on["test_damage_damage_per_strain"] = c;
  const auto composed = h.bond(on);

  Pairs a = test::random_pairs<Pairs>(300, 13);
  Pairs b = a;
  a.initialize(*plain);
  b.initialize(*composed);
  std::vector<double> l0(a.i.size()), peak(a.i.size(), 0.0);
  for (std::size_t k = 0; k < a.i.size(); ++k) l0[k] = (a.position[a.j[k]] - a.position[a.i[k]]).norm();
  std::size_t damaged = 0, broken_by_effect = 0, broken_by_beam = 0;
  for (int step = 0; step < 3; ++step) {
    test::deform(a, 300 + static_cast<std::uint64_t>(step), 0.004 * (step + 1), 0.2);
    test::deform(b, 300 + static_cast<std::uint64_t>(step), 0.004 * (step + 1), 0.2);
    a.compute(*plain);
    b.compute(*composed);
    for (std::size_t k = 0; k < a.i.size(); ++k) {
      if (a.broken[k]) {  // the beam broke it: the effect leaves it so
        CHECK(b.broken[k]);
        ++broken_by_beam;
        continue;
      }
      // The effect's own arithmetic, repeated: the same operations give the same bits.
      const double length = (a.position[a.j[k]] - a.position[a.i[k]]).norm();
      peak[k] = std::max(peak[k], (length - l0[k]) / l0[k]);
      const double damage = std::min(1.0, c * peak[k]);
      if (damage >= 1) {
        CHECK(b.broken[k]);
        ++broken_by_effect;
        continue;
      }
      REQUIRE_FALSE(b.broken[k]);
      damaged += damage > 0;
      const double intact = 1 - damage;
      CHECK(same_bits(b.force[k], Vec3(a.force[k] * intact)));
      CHECK(same_bits(b.torque_i[k], Vec3(a.torque_i[k] * intact)));
      CHECK(same_bits(b.torque_j[k], Vec3(a.torque_j[k] * intact)));
      CHECK(same_bits(b.energy[k], a.energy[k] * intact));
    }
  }
  MESSAGE(damaged, " damaged bond evaluations, ", broken_by_effect, " breaks by the effect, ", broken_by_beam,
          " by the beam");
  CHECK(damaged > 100);
  CHECK(broken_by_effect > 0);
}

}  // namespace shard
