// A bond effect's own state is checkpointed with the bond: the crush_cube scene with test_damage
// on (tests/plugin_api/CMakeLists.txt), stopped at step k and restarted, ends bit for bit where
// the uninterrupted run ends, break log and bond state included.
#include <sstream>

#include "../reliability/reliability_fixtures.hpp"
#include "shard/app/run_command.hpp"
#include "shard/run_file.hpp"

using namespace shard;
using namespace shard::test;

namespace {

// 30 per unit strain: a bond is fully damaged at 3.3 % stretch, a size at which the cube's
// crushing breaks bonds through the effect as well as the beam.
RunOptions options_for(const std::filesystem::path& out, bool effect_on) {
  RunOptions o;
  o.scene = kScenes / "crush_cube.toml";
  o.out_dir = out;
  o.quiet = true;
  o.plugin_dirs = {EFFECT_PLUGIN_DIR};
  if (effect_on) o.overrides = parse_overrides({"bond.test_damage_damage_per_strain=30"});
  return o;
}

}  // namespace

TEST_CASE("a run with a bond effect, interrupted and restarted, ends bit for bit as the uninterrupted run") {
  std::ostringstream log;
  const RunSummary plain = run_scene(options_for(scratch("effect_plain"), false), log);
  const auto reference_dir = scratch("effect_reference");
  const RunSummary reference = run_scene(options_for(reference_dir, true), log);
  // The effect acts: the damaged bonds transmit less, so the crushing differs from plain beam_bond.
  REQUIRE(reference.bonds_broken > 10);
  CHECK(reference.peak_load != plain.peak_load);
  MESSAGE("plain: peak ", plain.peak_load, " N, ", plain.bonds_broken, " broken; test_damage 30: peak ",
          reference.peak_load, " N, ", reference.bonds_broken, " broken");
  // The run records the effect's version and file beside the law's.
  bool recorded = false;
  for (const auto& [plugin, about] : RunFile(reference_dir / "run.h5").metadata().plugins)
    recorded = recorded || (plugin == "bond_effect/test_damage" && about.find("version=0.1.0;") == 0);
  CHECK(recorded);
  const Checkpoint final_reference = read_checkpoint(reference_dir / "run.checkpoint.h5");
  REQUIRE(final_reference.simulation.bonds.stride == 9 + 2);  // beam_bond's 9 doubles, then l0 and e_peak

  const std::int64_t first_break = final_reference.simulation.events.front().step;
  for (const std::int64_t k : {first_break - 3, first_break + 41}) {
    CAPTURE(k);
    const auto dir = scratch("effect_interrupted_" + std::to_string(k));
    RunOptions first = options_for(dir, true);
    first.interrupt_at_step = k;
    REQUIRE(run_scene(first, log).interrupted());
    RunOptions second = options_for(dir, true);
    second.scene.clear();
    second.overrides.clear();  // the run file holds the resolved scene
    second.restart = dir / "run.h5";
    const RunSummary resumed = run_scene(second, log);
    CHECK(resumed.restarted_from == k);
    CHECK(resumed.steps == reference.steps);
    CHECK(resumed.bonds_broken == reference.bonds_broken);
    CHECK(resumed.peak_load == reference.peak_load);
    require_identical(read_checkpoint(dir / "run.checkpoint.h5").simulation, final_reference.simulation);
  }
}
