// [stop] rest_speed and rest_time (docs/how-to/parameter-sweep.md, "Run to rest"): a sphere dropped onto a floor
// bounces with restitution 0.5 and comes to rest; the rule ends the run at the first step after
// every particle stayed slower than rest_speed for rest_time, within the time the bounces predict.
// Bad values are refused with the key and the fix.
#include <doctest/doctest.h>

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "driver_fixtures.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/scene_rules.hpp"
#include "shard/scene.hpp"

using namespace shard;
using namespace shard::driver;
using shard::test::plugins;
using shard::test::scratch;

namespace {

constexpr double kG = 9.81, kDrop = 0.05, kRestitution = 0.5;  // m/s^2, m (gap under the sphere), -
constexpr double kRestSpeed = 0.01, kRestTime = 0.05;            // m/s, s
constexpr double kRadius = 0.002;                                // m

// One 4 mm cake sphere kDrop above a plane floor, at rest; Hertz-Mindlin with e = 0.5.
std::string drop_scene(double duration, const std::string& stop) {
  return fmt::format(R"([simulation]
duration = {}
dt = 5e-6
gravity = [0, 0, -9.81]

[material]
density = 3720

[generator]
plugin = "box_fill"
min_corner = [0, 0, {}]
max_corner = [0.004, 0.004, {}]
diameter_min = 0.004
diameter_max = 0.004
lattice = "cubic"

[contact]
plugin = "hertz_mindlin"
shear_modulus = 10e6
poisson_ratio = 0.25
friction = 0.5
restitution = {}

[[wall]]
name = "floor"
shape = "plane"
point = [0, 0, 0]
normal = [0, 0, 1]

[stop]
{}
)",
                     duration, kDrop, kDrop + 2 * kRadius, kRestitution, stop);
}

std::filesystem::path write_scene(const std::filesystem::path& dir, const std::string& text) {
  const auto file = dir / "drop.toml";
  std::ofstream(file) << text;
  return file;
}

// The largest particle speed after every step of the loop (and at its start), with the time.
class SpeedLog : public RunObserver {
 public:
  std::vector<double> time, speed;
  void on_start(RunState& r) override { note(r); }
  void on_step(RunState& r) override { note(r); }

 private:
  void note(const RunState& r) {
    double v2 = 0;
    for (const Vec3& v : r.sim.particles().velocity) v2 = std::max(v2, v.squaredNorm());
    time.push_back(r.sim.time());
    speed.push_back(std::sqrt(v2));
  }
};

std::string load_error(const std::string& stop, double duration = 0.5) {
  const auto dir = scratch("rest_stop_errors");
  try {
    load_scene(write_scene(dir, drop_scene(duration, stop)), plugins());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("run to rest: a sphere bouncing on a floor stops the run once it stayed slower than rest_speed") {
  const auto dir = scratch("rest_stop_drop");
  RunSpec spec;
  spec.scene = write_scene(dir, drop_scene(1.0, fmt::format("rest_speed = {}\nrest_time = {}", kRestSpeed, kRestTime)));
  spec.out_dir = dir / "out";
  spec.threads = 1;
  SceneRules rules;
  SpeedLog log;
  std::vector<RunObserver*> observers = rules.observers();
  observers.insert(observers.begin(), &log);  // records the step the rule ends on too
  const RunResult r = run(spec, plugins(), observers);
  REQUIRE(r.stop == StopReason::Rest);
  MESSAGE(r.stop_reason << "; stopped at t = " << r.time << " s after " << r.steps << " steps");

  // The rule's definition, step by step: the stop step and every step back to rest_time before it
  // are below rest_speed, and the step before that window is not (else it would have stopped earlier).
  REQUIRE(log.time.back() == r.time);
  std::size_t first_still = log.time.size() - 1;
  while (first_still > 0 && log.speed[first_still - 1] < kRestSpeed) --first_still;
  CHECK(log.speed[first_still - 1] >= kRestSpeed);
  const double still_for = r.time - log.time[first_still];
  const double dt = log.time[1] - log.time[0];
  CHECK(still_for >= kRestTime - 0.5 * dt);
  CHECK(still_for < kRestTime + 0.5 * dt);

  // Physics: dropped from rest through kDrop, the sphere strikes at v0 = sqrt(2 g h) and leaves the
  // n-th bounce at e^n v0, flying 2 e^n v0 / g. Every bounce that leaves at >= rest_speed moves it
  // faster than rest_speed for all but 2 rest_speed / g = 2 ms around its apex (< rest_time), so
  // the run cannot be at rest before those flights are over: lower bound. The bounces after them
  // add at most the rest of the geometric series, 2 e^(N+1) v0 / (g (1 - e)); each contact lasts
  // ~1 ms (Hertz, t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5) = 0.5-1 ms from 1 m/s down to 0.01 m/s), and
  // the sphere resting on its Hertz spring (damping ratio ~0.2 for e = 0.5, period ~2 ms) loses
  // half its speed per millisecond: 1 ms per bounce plus 10 ms is a generous upper bound. The
  // realised e at dt = 5 us (~90 steps per contact at 1 m/s, more when slower) is within 0.1 % of
  // 0.5 (test_scene_materials: 0.05 % at 1 us and 340 steps per contact), so the bounds take e in
  // [0.495, 0.505], ten times that.
  const double v0 = std::sqrt(2 * kG * kDrop), fall = v0 / kG;
  int bounces = 0;  // N: bounces leaving at >= rest_speed (with the smaller e: fewest)
  double flights_low = 0;
  for (double v = v0 * 0.495; v >= kRestSpeed * 1.01; v *= 0.495, ++bounces) flights_low += 2 * v / kG;
  double v_last = v0 * std::pow(0.505, bounces);  // the larger e: the largest flights after them
  const double tail = 2 * v_last * 0.505 / (kG * (1 - 0.505));
  const double flights_high = 2 * v0 * 0.505 * (1 - std::pow(0.505, bounces)) / (kG * (1 - 0.505));
  const double lower = fall + flights_low + kRestTime;
  const double upper = fall + flights_high + tail + 1e-3 * (bounces + 5) + 0.01 + kRestTime;
  MESSAGE("bounces above rest_speed: " << bounces << "; stop expected in [" << lower << ", " << upper << "] s");
  CHECK(bounces == 6);  // v0 = 0.990 m/s, 0.990 * 0.5^6 = 0.0155 m/s >= 0.01 > 0.0077
  CHECK(r.time >= lower);
  CHECK(r.time <= upper);

  // At rest for real: 0.1 s on without the rule, the sphere stays on the floor, slower than rest_speed.
  RunSpec on = spec;
  on.scene = write_scene(dir, drop_scene(r.time + 0.1, ""));
  on.out_dir = dir / "on";
  SceneRules plain;
  SpeedLog after;
  std::vector<RunObserver*> watch = plain.observers();
  watch.push_back(&after);
  const RunResult longer = run(on, plugins(), watch);
  CHECK(longer.stop == StopReason::Duration);
  double fastest_after = 0;
  for (std::size_t k = 0; k < after.time.size(); ++k)
    if (after.time[k] >= log.time[first_still]) fastest_after = std::max(fastest_after, after.speed[k]);
  CHECK(fastest_after < kRestSpeed);
}

TEST_CASE("run to rest: bad [stop] rest_speed / rest_time values are refused with the key and the fix") {
  CHECK(load_error("rest_speed = 0.01\nrest_time = 0.05").empty());
  const std::string no_time = load_error("rest_speed = 0.01");
  CHECK(no_time.find("drop.toml:") != std::string::npos);
  CHECK(no_time.find("[stop] rest_speed needs rest_time too") != std::string::npos);
  CHECK(load_error("rest_time = 0.05").find("[stop] rest_time needs rest_speed too") != std::string::npos);
  CHECK(load_error("rest_speed = -0.01\nrest_time = 0.05").find("[stop] rest_speed = -0.01 must be positive") !=
        std::string::npos);
  CHECK(load_error("rest_speed = 0\nrest_time = 0.05").find("[stop] rest_speed = 0 must be positive") !=
        std::string::npos);
  CHECK(load_error("rest_speed = 0.01\nrest_time = 0").find("[stop] rest_time = 0 must be positive") !=
        std::string::npos);
  CHECK(load_error("rest_speed = 0.01\nrest_time = 0.5", 0.5).find("is not shorter than [simulation] duration") !=
        std::string::npos);
  CHECK(load_error("rest_speed = \"slow\"\nrest_time = 0.05").find("[stop] rest_speed must be a number") !=
        std::string::npos);
  CHECK(load_error("rest_sped = 0.01").find("unknown key 'rest_sped' in [stop] (did you mean 'rest_speed'?)") !=
        std::string::npos);
}
