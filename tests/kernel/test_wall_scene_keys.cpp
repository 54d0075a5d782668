// The [[wall]] keys of spinning walls and belts: what they set, and bad input refused with the
// file, line, column and key, and the fix.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "kernel_fixtures.hpp"
#include "shard/particles.hpp"
#include "shard/scene.hpp"

using namespace shard;

namespace {

const std::string kScene = R"([simulation]
duration = 0.001
dt = 1e-6
seed = 1

[material]
density = 2500

[generator]
plugin = "box_fill"
min_corner = [0, 0, 0.01]
max_corner = [0.008, 0.008, 0.018]
diameter_min = 0.004
diameter_max = 0.004
lattice = "cubic"
bond = false

[contact]
plugin = "linear_spring"
normal_stiffness = 1e4

[[wall]]
name = "w"
)";

// Loads kScene with `wall_keys` for the wall (line 24 on) and `table` beside it as table.csv.
Scene scene_with(const std::string& name, const std::string& wall_keys, const std::string& table = "") {
  const auto dir = std::filesystem::temp_directory_path() / ("shard_wall_keys_" + name);
  std::filesystem::create_directories(dir);
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

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

const std::string kPlane = "shape = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n";
const std::string kCylinder = "shape = \"cylinder\"\npoint = [0, 0, 0]\naxis = [0, 1, 0]\nradius = 0.01\nlength = 0.1\n";

}  // namespace

TEST_CASE("spin and belt keys set the wall's rotation and surface velocity") {
  const Scene rpm = scene_with("rpm", kCylinder + "rotation_axis = [0, 2, 0]\nrpm = 30\nramp = \"1-cos\"\nramp_time = 0.5\n");
  const WallMotion& m = rpm.walls[0].motion;
  CHECK(m.spins);
  CHECK(m.spin_axis == Vec3(0, 1, 0));                            // normalised
  CHECK(m.spin_centre == Vec3::Zero());                           // the cylinder's point by default
  CHECK(m.angular_speed == doctest::Approx(std::numbers::pi));    // 30 rpm = pi rad/s
  CHECK(m.angular_speed_at(0.25) == doctest::Approx(0.5 * std::numbers::pi));  // half way up the 1-cos ramp
  CHECK(m.angle_at(1.5) == doctest::Approx(std::numbers::pi * (1.5 - 0.25)));  // the ramp costs T/2

  const Scene flap = scene_with("flap", kPlane + "rotation_axis = [1, 0, 0]\nrotation_point = [0, 0, 0.05]\n"
                                                 "rotation_table = \"table.csv\"\n",
                                "time,angle\n0,0\n0.1,0.5\n0.2,0\n");
  const WallMotion& f = flap.walls[0].motion;
  CHECK(f.spin_centre == Vec3(0, 0, 0.05));
  CHECK(f.angle_at(0.05) == doctest::Approx(0.25));
  CHECK(f.angular_speed_at(0.15) == doctest::Approx(-5.0));

  const Scene belt = scene_with("belt", kPlane + "belt_speed = 1.5\nbelt_direction = [3, 4, 0]\n");
  CHECK(belt.walls[0].surface_velocity.isApprox(Vec3(0.9, 1.2, 0), 1e-15));
  CHECK_FALSE(belt.walls[0].motion.spins);
  const Scene vector = scene_with("vector", kPlane + "surface_velocity = [0, 0.3, 0]\n");
  CHECK(vector.walls[0].surface_velocity == Vec3(0, 0.3, 0));
}

TEST_CASE("bad spin and belt keys name the file, line, column, key and fix") {
  // The wall's keys start on line 24 of scene.toml; plane keys take 3 lines, cylinder keys 5.
  CHECK(has(error_of("zero", kPlane + "rotation_axis = [0, 0, 0]\nangular_velocity = 1\n"),
            "scene.toml:27:17: [wall] rotation_axis must not be the zero vector"));
  CHECK(has(error_of("noaxis", kPlane + "angular_velocity = 2\n"),
            "scene.toml:27:20: [wall] angular_velocity needs rotation_axis"));
  CHECK(has(error_of("nospeed", kPlane + "rotation_axis = [0, 0, 1]\n"),
            "[wall] rotation_axis is given without a speed: add angular_velocity [rad/s], rpm, or a rotation_table"));
  CHECK(has(error_of("twospeeds", kPlane + "rotation_axis = [0, 0, 1]\nangular_velocity = 1\nrpm = 10\n"),
            "scene.toml:29:7: [wall] rpm is one of angular_velocity, rpm and rotation_table"));
  const auto backwards = error_of("backwards", kPlane + "rotation_axis = [1, 0, 0]\nrotation_table = \"table.csv\"\n",
                                  "time,angular_velocity\n0,0\n0.2,1\n0.1,2\n");
  CHECK(has(backwards, "table.csv:4:1: time 0.1 s is not later than 0.2 s on line 3"));
  CHECK(has(backwards, "(read for [wall] rotation_table at "));
  CHECK(has(backwards, "scene.toml:28:18)"));
  CHECK(has(error_of("column", kPlane + "rotation_axis = [1, 0, 0]\nrotation_table = \"table.csv\"\n",
                     "time,displacement\n0,0\n1,1\n"),
            "table.csv:1:6: unknown column 'displacement' in the rotation_table; the columns are time [s] and either "
            "angle [rad] or angular_velocity [rad/s]"));
  CHECK(has(error_of("cylbelt", kCylinder + "belt_speed = 1\nbelt_direction = [1, 0, 0]\n"),
            "scene.toml:29:14: [wall] belt_speed has no meaning on a cylinder"));
  CHECK(has(error_of("cylbelt2", kCylinder + "surface_velocity = [1, 0, 0]\n"),
            "make it a turning roller instead, rotation_axis = its axis and angular_velocity = belt speed / radius"));
  CHECK(has(error_of("across", kPlane + "surface_velocity = [1, 0, 0.5]\n"),
            "scene.toml:27:20: [wall] surface_velocity has 0.5 m/s along the plane's normal"));
  CHECK(has(error_of("nodir", kPlane + "belt_speed = 1\n"),
            "[wall] belt_direction is missing or zero: the belt runs along it"));
  CHECK(has(error_of("both", kPlane + "belt_speed = 1\nbelt_direction = [1, 0, 0]\nsurface_velocity = [1, 0, 0]\n"),
            "[wall] surface_velocity is given with belt_speed or belt_direction"));
  const auto typo = error_of("typo", kPlane + "rotation_axs = [0, 0, 1]\n");
  CHECK(has(typo, "scene.toml:27:16: unknown key 'rotation_axs' in [wall] (did you mean 'rotation_axis'?)"));
}

TEST_CASE("unbreakable_zone marks the spheres whose centres start within it of the wall") {
  // kScene's box: two layers of 4 mm spheres, centres 2 and 6 mm above the plane at z = 0.01.
  const std::string floor = "shape = \"plane\"\npoint = [0, 0, 0.01]\nnormal = [0, 0, 1]\n";
  const Scene scene = scene_with("zone", floor + "unbreakable_zone = 0.003\n");
  CHECK(scene.walls[0].unbreakable_zone == doctest::Approx(0.003));
  const SceneInstance inst = instantiate(scene, test::plugins(), nullptr);
  const Particles& p = inst.simulation->particles();
  std::size_t marked = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const bool in_zone = (p.flags[k] & kUnbreakable) != 0;
    CHECK(in_zone == (p.position[k].z() < 0.013));
    marked += in_zone ? 1 : 0;
  }
  CHECK(marked == 4);
  CHECK(has(error_of("negative_zone", kPlane + "unbreakable_zone = -0.003\n"),
            "scene.toml:27:20: [wall] unbreakable_zone must be a distance >= 0 in m"));
}
