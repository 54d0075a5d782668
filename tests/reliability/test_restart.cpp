// Checkpoint/restart: a run stopped at step k and continued with --restart ends in the same
// state, bit for bit, as a run that was never stopped, and its run file holds the same series,
// break log and frames.
#include <sstream>

#include "reliability_fixtures.hpp"
#include "shard/app/run_command.hpp"
#include "shard/run_file.hpp"
#include "shard/scene.hpp"

using namespace shard;
using namespace shard::test;

namespace {

RunOptions options_for(const std::filesystem::path& out) {
  RunOptions o;
  o.scene = kScenes / "crush_cube.toml";
  o.out_dir = out;
  o.quiet = true;
  return o;
}

void require_same_run_files(const std::filesystem::path& a_path, const std::filesystem::path& b_path) {
  const RunFile a(a_path), b(b_path);
  CHECK(a.series_rows() == b.series_rows());
  for (const char* column : {"time", "kinetic_energy", "bond_energy", "contact_energy"})
    CHECK(same_bits(a.read_series(column), b.read_series(column)));
  for (const char* column : {"step", "bonds_intact", "bonds_broken", "contacts"})
    CHECK(same_bits(a.read_integer_series(column), b.read_integer_series(column)));
  REQUIRE(a.wall_names() == b.wall_names());
  for (const auto& wall : a.wall_names())
    for (const char* quantity : {"force", "torque", "displacement"})
      CHECK(same_bits(a.read_wall_series(wall, quantity), b.read_wall_series(wall, quantity)));
  const auto ea = a.read_break_events(), eb = b.read_break_events();
  REQUIRE(ea.size() == eb.size());
  for (std::size_t k = 0; k < ea.size(); ++k) CHECK((ea[k].step == eb[k].step && ea[k].id_i == eb[k].id_i));
  REQUIRE(a.frame_count() == b.frame_count());
  for (std::size_t k = 0; k < a.frame_count(); ++k) {
    const FrameData fa = a.read_frame(k), fb = b.read_frame(k);
    CHECK(fa.step == fb.step);
    CHECK(same_bits(fa.position, fb.position));
    CHECK(same_bits(fa.velocity, fb.velocity));
    CHECK(same_bits(fa.mass, fb.mass));  // the frames copied from the interrupted file too
    CHECK(fa.bond_i == fb.bond_i);
    CHECK(fa.bond_j == fb.bond_j);
  }
}

}  // namespace

TEST_CASE("interrupted at step k and restarted: final state and run file bit-identical to an uninterrupted run") {
  std::ostringstream log;
  const auto reference_dir = scratch("reference");
  const RunSummary reference = run_scene(options_for(reference_dir), log);
  // The scene must exercise what a checkpoint carries: contacts, broken bonds, a moving wall.
  REQUIRE(reference.bonds_broken > 10);
  REQUIRE(reference.steps > 500);
  const Checkpoint final_reference = read_checkpoint(reference_dir / "run.checkpoint.h5");
  REQUIRE(final_reference.simulation.step == reference.steps);
  REQUIRE(final_reference.simulation.contacts > 0);

  // k between frames (the checkpoint is then written by the interruption itself), on a frame,
  // before the first bond broke and after it.
  const std::int64_t first_break = final_reference.simulation.events.front().step;
  const std::int64_t second_frame = RunFile(reference_dir / "run.h5").read_frame(2).step;
  for (const std::int64_t k : {std::int64_t{137}, second_frame, first_break - 3, first_break + 41}) {
    CAPTURE(k);
    REQUIRE(k < reference.steps);
    const auto dir = scratch("interrupted_" + std::to_string(k));
    RunOptions first = options_for(dir);
    first.interrupt_at_step = k;
    const RunSummary stopped = run_scene(first, log);
    REQUIRE(stopped.interrupted());
    CHECK(stopped.steps == k);
    CHECK(stopped.checkpoint_step == k);

    RunOptions second = options_for(dir);
    second.scene.clear();
    second.restart = dir / "run.h5";
    const RunSummary resumed = run_scene(second, log);
    CHECK(resumed.restarted_from == k);
    CHECK(resumed.steps == reference.steps);
    CHECK(resumed.bonds_broken == reference.bonds_broken);
    CHECK(resumed.bonds_initial == reference.bonds_initial);  // also when bonds broke before the stop
    CHECK(resumed.peak_load == reference.peak_load);
    CHECK(same_bits(resumed.curve.force, reference.curve.force));
    require_identical(read_checkpoint(dir / "run.checkpoint.h5").simulation, final_reference.simulation);
    require_same_run_files(dir / "run.h5", reference_dir / "run.h5");
    CHECK_FALSE(std::filesystem::exists(dir / "run.interrupted.h5"));
  }
}

TEST_CASE("a restart that cannot proceed leaves the interrupted run untouched") {
  std::ostringstream log;
  const auto dir = scratch("no_checkpoint");
  RunOptions first = options_for(dir);
  first.interrupt_at_step = 50;
  run_scene(first, log);
  std::filesystem::remove(dir / "run.checkpoint.h5");
  RunOptions second = options_for(dir);
  second.restart = dir / "run.h5";
  CHECK_THROWS_WITH_AS(run_scene(second, log), doctest::Contains("no checkpoint"), CheckpointError);
  CHECK(RunFile(dir / "run.h5").frame_count() >= 1);

  RunOptions missing = options_for(dir);
  missing.restart = dir / "nothing.h5";
  CHECK_THROWS_WITH(run_scene(missing, log), doctest::Contains("no such run file"));
}

// The four-point beam's walls are not in name order in the scene (supports, then pins), while the
// file lists its wall groups by name: the series rows copied from the interrupted file must land
// under the walls they belong to (they once went to the scene's order of the names' order).
TEST_CASE("a restart keeps each wall's series under its own name") {
  std::ostringstream log;
  const auto options = [](const std::filesystem::path& out) {
    RunOptions o;
    o.scene = kSource / "scenes" / "four_point_bending_ci.toml";
    o.overrides = parse_overrides({"wall.pin_left.velocity=[0,0,-0.1]", "wall.pin_right.velocity=[0,0,-0.1]",
                                   "simulation.duration=0.004", "output.frame_interval=0.001",
                                   "output.series_interval=0.0001"});
    o.out_dir = out;
    o.quiet = true;
    return o;
  };
  const auto reference_dir = scratch("beam_reference"), dir = scratch("beam_interrupted");
  run_scene(options(reference_dir), log);
  RunOptions first = options(dir);
  first.interrupt_at_step = 200;
  REQUIRE(run_scene(first, log).interrupted());
  RunOptions second = options(dir);
  second.scene.clear();
  second.restart = dir / "run.h5";
  run_scene(second, log);
  const RunFile a(dir / "run.h5");
  // The pins move before the stop: their displacement column of the copied rows is not zero.
  CHECK(a.read_wall_series("pin_left", "displacement").at(10).z() < 0);
  require_same_run_files(dir / "run.h5", reference_dir / "run.h5");
}

// A run that ended at its duration is continued past it: --restart with a later
// simulation.duration ends where a run to that duration ends, bit for bit. Keys that made the
// state are refused.
TEST_CASE("a finished run extended by --restart --set simulation.duration equals one run to the later end") {
  std::ostringstream log;
  const auto reference_dir = scratch("extend_reference"), dir = scratch("extended");
  const RunSummary reference = run_scene(options_for(reference_dir), log);  // duration 0.004 s
  RunOptions first = options_for(dir);
  first.overrides = parse_overrides({"simulation.duration=0.0022"});
  const RunSummary short_run = run_scene(first, log);
  REQUIRE_FALSE(short_run.interrupted());
  REQUIRE(short_run.steps < reference.steps);

  RunOptions wrong = options_for(dir);
  wrong.scene.clear();
  wrong.restart = dir / "run.h5";
  wrong.overrides = parse_overrides({"simulation.duration=0.004", "bond.youngs_modulus=1e9"});
  CHECK_THROWS_WITH_AS(run_scene(wrong, log), doctest::Contains("only simulation.duration and [stop] keys"), SceneError);
  CHECK(RunFile(dir / "run.h5").frame_count() >= 1);  // refused before anything was touched

  RunOptions more = options_for(dir);
  more.scene.clear();
  more.restart = dir / "run.h5";
  // With the run's own value of a key given again (the first command line repeated): no change.
  more.overrides = parse_overrides({"simulation.global_damping=0.05", "simulation.duration=0.004"});
  const RunSummary extended = run_scene(more, log);
  CHECK(extended.restarted_from == short_run.steps);
  CHECK(extended.steps == reference.steps);
  CHECK(extended.bonds_broken == reference.bonds_broken);
  require_identical(read_checkpoint(dir / "run.checkpoint.h5").simulation,
                    read_checkpoint(reference_dir / "run.checkpoint.h5").simulation);
  require_same_run_files(dir / "run.h5", reference_dir / "run.h5");
}
