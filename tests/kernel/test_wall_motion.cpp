// Wall motion profiles: a ramp or a table gives the wall's displacement as a function of time.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "kernel_fixtures.hpp"
#include "shard/checkpoint.hpp"
#include "shard/scene.hpp"
#include "shard/wall_motion.hpp"

using namespace shard;

namespace {

// The integral of the wall's speed over [0, t] by 5-point Gauss-Legendre on 64 panels, split at
// the end of the ramp where the speed has a kink: independent of the closed forms in
// wall_motion.cpp. The rule is exact for polynomials of degree 9; on a panel of 1/64 of a
// half-period of cos the error is ~(pi/64)^10 / 10! ~ 1e-20 relative, far below rounding.
double integrated_speed(const WallMotion& m, double t) {
  static const std::array<double, 5> x = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                          0.9061798459386640};
  static const std::array<double, 5> w = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                          0.2369268850561891, 0.2369268850561891};
  auto panels = [&](double a, double b) {
    double sum = 0;
    const int n = 64;
    const double h = (b - a) / n;
    for (int p = 0; p < n; ++p) {
      const double mid = a + (p + 0.5) * h;
      for (std::size_t k = 0; k < 5; ++k) sum += 0.5 * h * w[k] * m.velocity_at(mid + 0.5 * h * x[k]).norm();
    }
    return sum;
  };
  const double split = std::min(t, m.ramp_time);
  return panels(0, split) + (t > split ? panels(split, t) : 0.0);
}

WallMotion ramp(WallRamp kind) {
  WallMotion m;
  m.velocity = Vec3(0, 0, -0.02);  // 20 mm/s, the lab's pin speed
  m.ramp = kind;
  m.ramp_time = 0.025;  // 25 ms
  return m;
}

// A sphere under gravity resting on a plane wall that is lifted along a ramp.
SimulationSetup lifted_sphere(const ContactModel& model, const WallMotion& motion) {
  SimulationSetup setup;
  setup.particles.add(Vec3(0, 0, 0.0049), 0.005, 2500.0);
  setup.particles.add(Vec3(0.02, 0, 0.0049), 0.004, 2500.0);
  Wall floor;
  floor.shape = WallShape::Plane;
  floor.axis = Vec3::UnitZ();
  floor.motion = motion;
  floor.velocity = motion.velocity;
  setup.walls.push_back(floor);
  setup.gravity = Vec3(0, 0, -9.81);
  setup.contact = &model;
  setup.dt = 1e-5;
  return setup;
}

std::filesystem::path temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("shard_wall_motion_" + name);
  std::filesystem::create_directories(dir);
  return dir;
}

const std::string kScene = R"([simulation]
duration = 0.001
dt = 1e-6
seed = 1

[material]
density = 2500

[generator]
plugin = "box_fill"
min_corner = [0, 0, 0]
max_corner = [0.008, 0.008, 0.008]
diameter_min = 0.004
diameter_max = 0.004
lattice = "cubic"
bond = false

[contact]
plugin = "linear_spring"
normal_stiffness = 1e4

[[wall]]
name = "floor"
shape = "plane"
point = [0, 0, 0]
normal = [0, 0, 1]
)";

// Loads kScene with `wall_keys` added to the floor and `table` written beside it as table.csv.
Scene scene_with(const std::string& name, const std::string& wall_keys, const std::string& table = "") {
  const auto dir = temp_dir(name);
  if (!table.empty()) std::ofstream(dir / "table.csv") << table;
  std::ofstream(dir / "scene.toml") << kScene << wall_keys;
  return load_scene(dir / "scene.toml", {}, test::plugins());
}

std::string error_of(const std::string& name, const std::string& wall_keys, const std::string& table = "") {
  try {
    scene_with(name, wall_keys, table);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a ramp's displacement is the integral of its speed to 1e-12, and it ends at full speed") {
  for (WallRamp kind : {WallRamp::OneMinusCos, WallRamp::Linear}) {
    const WallMotion m = ramp(kind);
    for (double f : {1e-3, 0.01, 0.3, 0.5, 0.99, 1.0, 1.7, 8.0}) {
      const double t = f * m.ramp_time;
      const double exact = integrated_speed(m, t);
      CHECK(std::abs(m.displacement_at(t).norm() - exact) <= 1e-12 * exact);
      CHECK(m.displacement_at(t).normalized().isApprox(Vec3(0, 0, -1), 1e-15));
    }
    // The ramp costs half its time at full speed: d(t) = V (t - T/2) once it is over.
    CHECK(m.displacement_at(0.1).z() == doctest::Approx(-0.02 * (0.1 - 0.0125)).epsilon(1e-14));
    CHECK(m.velocity_at(m.ramp_time).z() == -0.02);
    CHECK(m.velocity_at(0.0).norm() == 0.0);
    CHECK(m.displacement_at(0.0).norm() == 0.0);
  }
  // 1-cos: half the speed at half the ramp time, and no acceleration jump at either end (the
  // speed's slope at the ends is zero: v(T/100) ~ V (pi/100)^2 / 4).
  const WallMotion c = ramp(WallRamp::OneMinusCos);
  CHECK(c.velocity_at(0.0125).z() == doctest::Approx(-0.01).epsilon(1e-14));
  CHECK(c.velocity_at(0.00025).norm() == doctest::Approx(0.02 * std::pow(std::numbers::pi / 100, 2) / 4).epsilon(1e-3).scale(0));
}

TEST_CASE("a simulated ramped wall is at the profile's position at every step, not a sum of steps") {
  auto model = test::linear_spring(1e4, 0.5, 0.5);
  WallMotion m = ramp(WallRamp::OneMinusCos);
  m.velocity = Vec3(0, 0, 0.02);  // lifting the spheres
  Simulation sim(lifted_sphere(*model, m));
  CHECK(sim.walls()[0].velocity.norm() == 0.0);  // the ramp starts at rest
  for (int k = 0; k < 40; ++k) {
    sim.run(100);
    CHECK(sim.walls()[0].displacement == m.displacement_at(sim.time()));
    CHECK(sim.walls()[0].velocity == m.velocity_at(sim.time()));
  }
  CHECK(sim.time() > m.ramp_time);
  CHECK(sim.walls()[0].velocity.z() == 0.02);
}

TEST_CASE("a run restarted in the middle of a ramp continues bit for bit") {
  auto model = test::linear_spring(1e4, 0.5, 0.5);
  WallMotion m = ramp(WallRamp::OneMinusCos);
  m.velocity = Vec3(0, 0, 0.05);
  Simulation uninterrupted(lifted_sphere(*model, m));
  uninterrupted.run(1200);  // 12 ms: half way up the 25 ms ramp, the spheres riding on the floor
  const SimulationState middle = uninterrupted.export_state();
  const auto file = temp_dir("restart") / "mid_ramp.checkpoint.h5";
  write_checkpoint(file, Checkpoint{middle, {}, {}});
  Simulation restarted(lifted_sphere(*model, m));
  restarted.import_state(read_checkpoint(file).simulation);
  uninterrupted.run(2000);
  restarted.run(2000);
  CHECK(restarted.time() == uninterrupted.time());
  CHECK(restarted.walls()[0].displacement == uninterrupted.walls()[0].displacement);
  CHECK(restarted.walls()[0].force == uninterrupted.walls()[0].force);
  bool same = true;
  for (std::size_t k = 0; k < 2; ++k)
    same = same && restarted.particles().position[k] == uninterrupted.particles().position[k] &&
           restarted.particles().velocity[k] == uninterrupted.particles().velocity[k];
  CHECK(same);
  // The spheres were carried: the contact is real, so the comparison tests the dynamics.
  CHECK(uninterrupted.particles().position[0].z() > 0.0049 + 0.5 * uninterrupted.walls()[0].displacement.z());
}

TEST_CASE("a wall with a start time rests until then, then runs its profile as from t = 0") {
  // A pin held 10 ms while a beam settles under gravity, then a 1-cos ramp to 20 mm/s; a constant
  // velocity held the same way becomes a profile (a function of time, not a sum of steps).
  for (WallRamp kind : {WallRamp::OneMinusCos, WallRamp::None}) {
    WallMotion held = ramp(kind);
    if (kind == WallRamp::None) held.ramp_time = 0;
    held.start_time = 0.01;
    const WallMotion free = [&] {
      WallMotion m = held;
      m.start_time = 0;
      return m;
    }();
    CHECK(held.is_profile());
    for (double t : {0.0, 0.004, 0.01}) {
      CHECK(held.displacement_at(t).norm() == 0.0);
      CHECK(held.velocity_at(t - 1e-12).norm() == 0.0);
    }
    for (double t : {0.0101, 0.02, 0.035, 0.2}) {
      CHECK(held.displacement_at(t) == free.displacement_at(t - 0.01));
      CHECK(held.velocity_at(t) == free.velocity_at(t - 0.01));
    }
  }
  // In a run: the floor stays put through the hold (the spheres rest on it under gravity), then
  // lifts along the ramp, at the profile's position at every step.
  auto model = test::linear_spring(1e4, 0.5, 0.5);
  WallMotion m = ramp(WallRamp::OneMinusCos);
  m.velocity = Vec3(0, 0, 0.02);
  m.start_time = 0.01;
  Simulation sim(lifted_sphere(*model, m));
  sim.run(900);
  REQUIRE(sim.time() < 0.01);
  CHECK(sim.walls()[0].displacement.norm() == 0.0);
  CHECK(sim.walls()[0].velocity.norm() == 0.0);
  for (int k = 0; k < 30; ++k) {
    sim.run(100);
    CHECK(sim.walls()[0].displacement == m.displacement_at(sim.time()));
  }
  CHECK(sim.walls()[0].displacement.z() > 0.0);
}

TEST_CASE("a table wall follows its table, piecewise linear, and a velocity table is integrated exactly") {
  const Scene d = scene_with("displacement", "motion_table = \"table.csv\"\ndirection = [0, 0, 2]\n",
                             "# a stepwise pin displacement\ntime,displacement\n0,0\n0.01,0.001\n0.02,0.001\n0.03,0.004\n");
  const WallMotion& m = d.walls[0].motion;
  REQUIRE(m.is_profile());
  CHECK(m.displacement_at(0.01).z() == 0.001);
  CHECK(m.displacement_at(0.015).z() == 0.001);
  CHECK(m.displacement_at(0.005).z() == doctest::Approx(0.0005).epsilon(1e-15));
  CHECK(m.displacement_at(0.025).z() == doctest::Approx(0.0025).epsilon(1e-15));
  CHECK(m.velocity_at(0.025).z() == doctest::Approx(0.3).epsilon(1e-14));
  CHECK(m.displacement_at(0.04).z() == doctest::Approx(0.007).epsilon(1e-14));  // the last slope goes on
  CHECK(m.displacement_at(0.01).x() == 0.0);                                     // along the unit direction

  const Scene v = scene_with("velocity", "motion_table = \"table.csv\"\ndirection = [1, 0, 0]\n",
                             "time, velocity\n0, 0\n0.01, 0.1\n0.02, 0.1\n");
  const WallMotion& mv = v.walls[0].motion;
  // Speed rising linearly to 0.1 m/s in 10 ms (0.5 mm), then 10 ms at 0.1 m/s (1 mm).
  CHECK(mv.displacement_at(0.005).x() == doctest::Approx(0.5 * 10 * 0.005 * 0.005).epsilon(1e-14));
  CHECK(mv.displacement_at(0.02).x() == doctest::Approx(0.0015).epsilon(1e-14));
  CHECK(mv.displacement_at(0.03).x() == doctest::Approx(0.0025).epsilon(1e-14));
  CHECK(mv.velocity_at(0.005).x() == doctest::Approx(0.05).epsilon(1e-14));
  // The wall in a run sits where its table says.
  SceneInstance inst = instantiate(v, test::plugins(), [](const std::string&) {});
  inst.simulation->run(500);
  CHECK(inst.simulation->walls()[0].displacement == mv.displacement_at(inst.simulation->time()));
}

TEST_CASE("bad motion profiles give errors naming the file, line and the fix") {
  const auto column = error_of("column", "motion_table = \"table.csv\"\ndirection = [0, 0, 1]\n",
                               "time,displacment\n0,0\n1,1\n");
  CHECK(column.find("table.csv:1:6: unknown column 'displacment'") != std::string::npos);
  const auto order = error_of("order", "motion_table = \"table.csv\"\ndirection = [0, 0, 1]\n",
                              "time,velocity\n0,0\n# a comment\n0.2,1\n0.2,1\n");
  CHECK(order.find("table.csv:5:1: time 0.2 s is not later than 0.2 s on line 4") != std::string::npos);
  const auto number = error_of("number", "motion_table = \"table.csv\"\ndirection = [0, 0, 1]\n",
                               "time,velocity\n0,0\n0.1,fast\n");
  CHECK(number.find("table.csv:3:5: 'fast' is not a number") != std::string::npos);
  const auto start = error_of("start", "motion_table = \"table.csv\"\ndirection = [0, 0, 1]\n", "time,velocity\n1,0\n2,1\n");
  CHECK(start.find("must start at time 0") != std::string::npos);
  const auto missing = error_of("missing", "motion_table = \"nowhere.csv\"\ndirection = [0, 0, 1]\n");
  CHECK(missing.find("nowhere.csv: cannot open the wall's motion_table") != std::string::npos);
  CHECK(error_of("nodir", "motion_table = \"table.csv\"\n", "time,velocity\n0,0\n1,1\n").find("direction is missing") !=
        std::string::npos);
  CHECK(error_of("both", "velocity = [0, 0, 1]\nmotion_table = \"table.csv\"\ndirection = [0, 0, 1]\n",
                 "time,velocity\n0,0\n1,1\n")
            .find("velocity is given with a motion_table") != std::string::npos);
  const auto name = error_of("rampname", "velocity = [0, 0, 1]\nramp = \"cosine\"\nramp_time = 0.01\n");
  CHECK(name.find("scene.toml:28:8: [wall] ramp = 'cosine' is not a ramp; use \"1-cos\"") != std::string::npos);
  CHECK(error_of("ramptime", "velocity = [0, 0, 1]\nramp = \"1-cos\"\n").find("needs ramp_time") != std::string::npos);
  CHECK(error_of("lonetime", "velocity = [0, 0, 1]\nramp_time = 0.01\n").find("ramp_time is set without a ramp") !=
        std::string::npos);
  CHECK(error_of("ok", "velocity = [0, 0, 1]\nramp = \"linear\"\nramp_time = 0.01\n").empty());
  CHECK(error_of("held", "velocity = [0, 0, 1]\nstart_time = 0.02\n").empty());
  const auto negative = error_of("early", "velocity = [0, 0, 1]\nstart_time = -0.02\n");
  CHECK(negative.find("scene.toml:28:") != std::string::npos);
  CHECK(negative.find("start_time") != std::string::npos);
}

TEST_CASE("settling holds the walls, runs the clock up to zero and gives their motion back") {
  // Two spheres dropped 0.1 mm into a floor that is to lift along a ramp: while they settle the
  // floor stays put; afterwards the spheres rest at the overlap of their weight, and the floor runs
  // its ramp from t = 0 as if the run had begun there.
  const double k_n = 1e4;
  auto model = test::linear_spring(k_n, 0.5, 0.5);
  WallMotion m = ramp(WallRamp::OneMinusCos);
  m.velocity = Vec3(0, 0, 0.02);
  Simulation sim(lifted_sphere(*model, m));
  const double loading_dt = sim.dt();
  const double settling_dt = 0.5 * loading_dt;
  const auto steps = static_cast<std::int64_t>(std::ceil(0.05 / settling_dt));
  sim.begin_settling(static_cast<double>(steps) * settling_dt, 0.5, settling_dt);
  CHECK(sim.time() < 0);
  CHECK(sim.dt() == settling_dt);
  for (std::int64_t s = 0; s < steps; ++s) {
    sim.step();
    REQUIRE(sim.walls()[0].displacement.norm() == 0.0);
  }
  CHECK(std::abs(sim.time()) < 1e-9);
  sim.end_settling();
  CHECK(sim.time() == 0.0);
  CHECK(sim.step_count() == 0);
  CHECK(sim.dt() == loading_dt);
  // At rest on the floor at m g / k_n (linear_spring): to 1 % of that overlap.
  const Particles& p = sim.particles();
  for (std::size_t k = 0; k < 2; ++k) {
    const double overlap = p.radius[k] - p.position[k].z();
    CHECK(overlap == doctest::Approx(p.mass[k] * 9.81 / k_n).epsilon(0.01));
    CHECK(p.velocity[k].norm() < 1e-4);
  }
  sim.run(1000);
  CHECK(sim.walls()[0].displacement == m.displacement_at(sim.time()));
  CHECK(sim.walls()[0].displacement.z() > 0);
  // A wall seated after settling keeps its new place through a checkpoint.
  sim.shift_wall(0, Vec3(0, 0, -1e-4));
  Simulation restored(lifted_sphere(*model, m));
  restored.import_state(sim.export_state());
  CHECK(restored.walls()[0].point == sim.walls()[0].point);
  CHECK(restored.walls()[0].point.z() == doctest::Approx(-1e-4).scale(0));
}
