// A run that blows up stops within a few steps, naming the step, the particles and the cause,
// with the last good state kept as the checkpoint.
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "shard/driver/numerical_health.hpp"
#include "reliability_fixtures.hpp"
#include "../common/overlap_scene.hpp"
#include "shard/app/run_command.hpp"

using namespace shard;
using namespace shard::test;

namespace {

// The step number of a message that starts "step N (t = ..." (string scanning, not std::regex:
// GCC 12 warns falsely inside <regex> in the sanitizer build).
std::int64_t step_in(const std::string& message) {
  REQUIRE(message.rfind("step ", 0) == 0);
  const auto end = message.find(" (t = ");
  REQUIRE(end != std::string::npos);
  return std::stoll(message.substr(5, end - 5));
}

// A quiet run of `scene` into `dir`.
RunOptions quiet_run(const std::filesystem::path& scene, const std::filesystem::path& dir) {
  RunOptions o;
  o.scene = scene;
  o.out_dir = dir;
  o.quiet = true;
  return o;
}

// The NumericalError a run stops with; empty when it runs through.
std::string blow_up_message(const RunOptions& o, std::ostream& log) {
  try {
    run_scene(o, log);
  } catch (const NumericalError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a time step far above the bonds' critical step is stopped within a few steps, naming the cause") {
  std::ostringstream log;
  const auto dir = scratch("dt_too_large");
  RunOptions o = quiet_run(kScenes / "crush_cube.toml", dir);
  // The auto step of this scene is about 2.6e-6 s; 20 times that is far past every critical step.
  o.overrides = {{"simulation.dt", 5.2e-5}};
  std::string message;
  try {
    run_scene(o, log);
    FAIL("the unstable run was not stopped");
  } catch (const NumericalError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK(step_in(message) <= 30);  // checks every 10 steps; the growth is ~100x per step
  CHECK(message.find("the run blew up") != std::string::npos);
  CHECK(message.find("particle ids ") != std::string::npos);
  CHECK(message.find("above the critical step") != std::string::npos);
  CHECK(message.find("beam_bond") != std::string::npos);
  // The last good state: the checkpoint of step 0, which stays readable.
  CHECK(message.find("run.checkpoint.h5 (step 0)") != std::string::npos);
  const Checkpoint good = read_checkpoint(dir / "run.checkpoint.h5");
  CHECK(good.simulation.step == 0);
  for (const auto& v : good.simulation.particles.velocity) CHECK(v.allFinite());
}

TEST_CASE("heavy settling damping on a lattice: the automatic step settles it; the critical step blows up naming the damping") {
  std::ostringstream log;
  RunOptions o = quiet_run(kScenes / "lattice_block.toml", scratch("damped_lattice_auto"));
  // The automatic step settles at critical / sqrt(1.5): the block stays at rest.
  const RunSummary automatic = run_scene(o, log);
  CHECK(automatic.dt > 0);

  // The same step given in the scene is kept through the settling, where 0.5 shortens the stable
  // step by 1 / sqrt(1.5).
  o.overrides = {{"simulation.dt", automatic.dt}};
  o.out_dir = scratch("damped_lattice");
  const std::string message = blow_up_message(o, log);
  CAPTURE(message);
  REQUIRE_FALSE(message.empty());
  CHECK(message.find("Cundall's damping [simulation] settle_damping = 0.5") != std::string::npos);
  CHECK(message.find("of beam_bond") != std::string::npos);
  CHECK(message.find("above the critical step") == std::string::npos);
  // The step the message advises settles the same lattice to rest.
  const std::string advice = "set [simulation] dt to at most ";
  const auto at = message.find(advice);
  REQUIRE(at != std::string::npos);
  const double advised = std::stod(message.substr(at + advice.size()));
  CHECK(advised == doctest::Approx(automatic.dt / std::sqrt(1.5)).epsilon(1e-3));
  o.overrides = {{"simulation.dt", advised}};
  o.out_dir = scratch("damped_lattice_advised_step");
  CHECK_NOTHROW(run_scene(o, log));
}

TEST_CASE("spheres generated inside one another: the blow-up names the overlapping initial packing") {
  std::ostringstream log;
  const auto dir = scratch("overlap");
  const RunOptions o = quiet_run(test::write_overlap_scene(dir), dir);
  const std::string message = blow_up_message(o, log);
  CAPTURE(message);
  REQUIRE_FALSE(message.empty());
  CHECK(step_in(message) <= 20);
  CHECK(message.find("overlapping initial packing: particles 0 and 1 overlapped by 190 %") != std::string::npos);
  CHECK(message.find("critical step") == std::string::npos);
}
