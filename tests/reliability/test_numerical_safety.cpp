// A run that blows up stops within a few steps, naming the step, the particles and the cause,
// with the last good state kept as the checkpoint.
#include <sstream>

#include "shard/driver/numerical_health.hpp"
#include "reliability_fixtures.hpp"
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

}  // namespace

TEST_CASE("a time step far above the bonds' critical step is stopped within a few steps, naming the cause") {
  std::ostringstream log;
  const auto dir = scratch("dt_too_large");
  RunOptions o;
  o.scene = kScenes / "crush_cube.toml";
  o.out_dir = dir;
  o.quiet = true;
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

TEST_CASE("spheres generated inside one another: the blow-up names the overlapping initial packing") {
  std::ostringstream log;
  const auto dir = scratch("overlap");
  // Two 1 mm spheres 0.1 mm apart: 190 % of the radius overlap. dt = 1e-5 s is below the
  // spring's critical step (2.3e-5 s), so the overlap alone is named as the cause; with dt
  // "auto" (1.1e-6 s) the spring resolves even this, and nothing blows up.
  std::ofstream(dir / "spheres.csv") << "x,y,z,r\n0,0,0.002,0.001\n0,0,0.0021,0.001\n0.004,0,0.002,0.001\n";
  std::ofstream(dir / "scene.toml") << R"([simulation]
duration = 0.001
dt = 1e-5
[material]
density = 2500
[generator]
plugin = "from_file"
spheres = "spheres.csv"
bonds = ""
max_overlap = 2.0
[contact]
plugin = "linear_spring"
normal_stiffness = 1e5
)";
  RunOptions o;
  o.scene = dir / "scene.toml";
  o.out_dir = dir;
  o.quiet = true;
  std::string message;
  try {
    run_scene(o, log);
  } catch (const NumericalError& e) {
    message = e.what();
  }
  CAPTURE(message);
  REQUIRE_FALSE(message.empty());
  CHECK(step_in(message) <= 20);
  CHECK(message.find("overlapping initial packing: particles 0 and 1 overlapped by 190 %") != std::string::npos);
  CHECK(message.find("critical step") == std::string::npos);
}
