// Materials (docs/reference/materials.md): [[material]] entries and [[material_pair]] rows, the bodies' and
// walls' materials, the per-pair laws through whole runs (sliding deceleration mu_pair g on two
// walls, restitution per pair from head-on impacts), and the bad-input errors.
#include <doctest/doctest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "shard/app/run_command.hpp"
#include "shard/checkpoint.hpp"
#include "../common/installed_plugins.hpp"
#include "shard/plugin_host.hpp"
#include "shard/run_file.hpp"
#include "shard/scene.hpp"

using namespace shard;

namespace {

using testing::plugins;

constexpr double kRadius = 0.002;  // m: every test body is one 4 mm sphere
constexpr double kDensity = 3720;  // kg/m^3, filter cake

// Cake (the seed's reduced G), a rubber belt and a steel chute; each pair its own mu and e.
const std::string kMaterials = R"(
[[material]]
name = "cake"
density = 3720
shear_modulus = 10e6
poisson_ratio = 0.25

[[material]]
name = "rubber"
shear_modulus = 1e6
poisson_ratio = 0.45

[[material]]
name = "steel"
shear_modulus = 79e9
poisson_ratio = 0.3

[[material_pair]]
materials = ["cake", "cake"]
friction = 0.5
restitution = 0.4

[[material_pair]]
materials = ["cake", "rubber"]
friction = 0.8
restitution = 0.3

[[material_pair]]
materials = ["steel", "cake"]
friction = 0.2
restitution = 0.7

[contact]
plugin = "hertz_mindlin"
)";

std::string simulation(double duration, const std::string& gravity, const std::string& dt = "\"auto\"") {
  return "[simulation]\nduration = " + std::to_string(duration) + "\ndt = " + dt + "\ngravity = " + gravity + "\n";
}

// One sphere of `material` centred at `position`, moving at `velocity`.
std::string sphere(const std::string& name, const std::string& material, const std::string& position,
                   const std::string& velocity) {
  return "\n[[body]]\nname = \"" + name + "\"\nmaterial = \"" + material + "\"\nposition = " + position +
         "\nvelocity = " + velocity +
         "\n[body.generator]\nplugin = \"box_fill\"\nmin_corner = [0, 0, 0]\nmax_corner = [0.004, 0.004, 0.004]\n"
         "diameter_min = 0.004\ndiameter_max = 0.004\nlattice = \"cubic\"\n";
}

std::string wall(const std::string& text) { return "\n[[wall]]\n" + text + "\n"; }

Scene load(const std::string& text) { return load_scene_text(text, "materials.toml", {}, plugins()); }

std::string error_of(const std::string& text) {
  try {
    instantiate(load(text), plugins(), {});
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The velocity and spin of the particle of body `id` (one sphere per body).
std::size_t particle_of(const Simulation& sim, std::int32_t id) {
  const auto& p = sim.particles();
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.body[k] == id) return k;
  FAIL("no particle of body " << id);
  return 0;
}

// Johnson's E* of two materials from G and nu (what docs/reference/materials.md states).
double e_star(double g1, double nu1, double g2, double nu2) {
  const double e1 = 2 * g1 * (1 + nu1), e2 = 2 * g2 * (1 + nu2);
  return 1.0 / ((1 - nu1 * nu1) / e1 + (1 - nu2 * nu2) / e2);
}

}  // namespace

TEST_CASE("materials load: densities, law parameters per material, pairs resolved and symmetric") {
  const std::string text = simulation(0.01, "[0, 0, -9.81]") + kMaterials +
                           wall("name = \"chute\"\nshape = \"plane\"\nnormal = [0, 0, 1]\nmaterial = \"steel\"") +
                           sphere("a", "cake", "[0, 0, 0.01]", "[0, 0, 0]");
  const Scene s = load(text);
  REQUIRE(s.material_table);
  REQUIRE(s.materials.size() == 3);
  CHECK(s.materials[0].density == kDensity);
  CHECK(s.materials[2].density == 0);  // steel: walls only
  CHECK(s.materials[1].law.number("shear_modulus") == 1e6);
  CHECK(s.walls[0].material == 2);
  CHECK(s.bodies[0].material == 0);
  REQUIRE(s.material_pairs.size() == 9);
  CHECK(s.material_pairs[0 * 3 + 2].number("friction") == 0.2);
  CHECK(s.material_pairs[2 * 3 + 0].number("restitution") == 0.7);
  // rubber-steel never meet (no body is of either): the law's defaults fill it, unread.
  CHECK(s.material_pairs[1 * 3 + 2].number("friction") == 0.67);
  const SceneInstance inst = instantiate(s, plugins(), {});
  CHECK(inst.simulation->particles().material[0] == 0);
}

TEST_CASE("a sphere sliding on two walls of different materials decelerates at mu_pair g on each") {
  // Two cylinders of radius 0.4 m with their axes along x (the top a straight line), one of rubber,
  // one of steel; a cake sphere on each, at its static Hertz overlap, launched at 2 m/s along x.
  // Sliding lasts 2 v0 / (7 mu g) >= 73 ms; the check runs 30 ms. Each step's Coulomb force is
  // mu F_n and the wall's normal is vertical, so -dv_x = mu (g t + v_z) exactly (to round-off);
  // started at rest on its Hertz spring the sphere keeps v_z ~ 0, so it decelerates at mu g.
  const double m = kDensity * 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius, g = 9.81;
  const auto rest_overlap = [&](double e) { return std::pow(m * g / (4.0 / 3.0 * e * std::sqrt(kRadius)), 2.0 / 3.0); };
  const double on_rubber = kRadius - rest_overlap(e_star(10e6, 0.25, 1e6, 0.45));
  const double on_steel = kRadius - rest_overlap(e_star(10e6, 0.25, 79e9, 0.3));
  const std::string text =
      simulation(0.03, "[0, 0, -9.81]") + kMaterials +
      wall("name = \"belt\"\nshape = \"cylinder\"\npoint = [0, 0, -0.4]\naxis = [1, 0, 0]\nradius = 0.4\nlength = 1\n"
           "material = \"rubber\"") +
      wall("name = \"chute\"\nshape = \"cylinder\"\npoint = [0, 1, -0.4]\naxis = [1, 0, 0]\nradius = 0.4\nlength = 1\n"
           "material = \"steel\"") +
      sphere("on_belt", "cake", fmt::format("[-0.3, 0, {:.17g}]", on_rubber), "[2, 0, 0]") +
      sphere("on_chute", "cake", fmt::format("[-0.3, 1, {:.17g}]", on_steel), "[2, 0, 0]");
  const SceneInstance inst = instantiate(load(text), plugins(), {});
  Simulation& sim = *inst.simulation;
  const auto steps = static_cast<std::int64_t>(std::ceil(0.03 / sim.dt()));
  sim.run(steps);
  const double t = sim.time();
  const double mu[] = {0.8, 0.2};
  for (std::int32_t body = 0; body < 2; ++body) {
    CAPTURE(body);
    const std::size_t k = particle_of(sim, body);
    const Vec3 v = sim.particles().velocity[k];
    const double slip = v.x() - sim.particles().omega[k].y() * kRadius;  // contact point speed along x
    const double deceleration = (2.0 - v.x()) / t;
    MESSAGE("mu " << mu[body] << ": deceleration " << deceleration << " m/s^2 (mu g " << mu[body] * g << "), v_z "
                  << v.z() << " m/s, slip " << slip << " m/s after " << t << " s");
    CHECK(slip > 0.1);  // still sliding
    CHECK((2.0 - v.x()) == doctest::Approx(mu[body] * (g * t + v.z())).epsilon(1e-9));
    CHECK(deceleration == doctest::Approx(mu[body] * g).epsilon(0.005));
  }
}

TEST_CASE("restitution per pair: head-on impacts realise each pair's e within 0.5 %") {
  // No gravity: a cake sphere at 1 m/s onto a steel plane (e = 0.7), one onto a rubber plane
  // (e = 0.3), and two cake spheres head on (e = 0.4). The law realises e for any impact speed
  // up to the integration error: at dt = 1 us the shortest contact (cake on cake, 0.34 ms) spans
  // ~340 steps, and the realised e is within 0.05 % (measured: 0.700087, 0.299865, 0.39987); 0.5 %
  // is ten times that, still 4 to 10 times below the gap between the pairs' values (0.1 and more
  // apart), so a pair reading another pair's e fails. At the auto step (26 us, 13 steps per contact
  // at 1 m/s) the realised e falls 1.4 to 5.4 % short (time step, not materials).
  const std::string text =
      simulation(0.004, "[0, 0, 0]", "1e-6") + kMaterials +
      wall("name = \"steel_floor\"\nshape = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nmaterial = \"steel\"") +
      wall("name = \"rubber_side\"\nshape = \"plane\"\npoint = [0.5, 0, 0]\nnormal = [-1, 0, 0]\nmaterial = \"rubber\"") +
      sphere("onto_steel", "cake", "[0, 0, 0.0025]", "[0, 0, -1]") +
      sphere("onto_rubber", "cake", "[0.4975, 0, 0.3]", "[1, 0, 0]") +
      sphere("left", "cake", "[0.2, 0.2, 0.3]", "[0, 1, 0]") + sphere("right", "cake", "[0.2, 0.205, 0.3]", "[0, -1, 0]");
  const SceneInstance inst = instantiate(load(text), plugins(), {});
  Simulation& sim = *inst.simulation;
  sim.run(static_cast<std::int64_t>(std::ceil(0.004 / sim.dt())));
  const auto& p = sim.particles();
  const double onto_steel = p.velocity[particle_of(sim, 0)].z();
  const double onto_rubber = -p.velocity[particle_of(sim, 1)].x();
  const double pair = (p.velocity[particle_of(sim, 3)].y() - p.velocity[particle_of(sim, 2)].y()) / 2.0;
  MESSAGE("e realised: cake-steel " << onto_steel << " (set 0.7), cake-rubber " << onto_rubber
                                    << " (set 0.3), cake-cake " << pair << " (set 0.4)");
  CHECK(std::abs(onto_steel - 0.7) <= 0.005 * 0.7);
  CHECK(std::abs(onto_rubber - 0.3) <= 0.005 * 0.3);
  CHECK(std::abs(pair - 0.4) <= 0.005 * 0.4);
}

TEST_CASE("one [[material]] runs bit for bit as the same scene with [material] and [contact]") {
  const std::string body = sphere("a", "cake", "[0, 0, 0.0025]", "[0.3, 0, -1]");
  const std::string floor = wall("name = \"floor\"\nshape = \"plane\"\nnormal = [0, 0, 1]");
  const std::string table = simulation(0.01, "[0, 0, -9.81]") +
                            "[[material]]\nname = \"cake\"\ndensity = 3720\nshear_modulus = 10e6\npoisson_ratio = 0.25\n"
                            "[[material_pair]]\nmaterials = [\"*\", \"*\"]\nfriction = 0.5\nrestitution = 0.4\n"
                            "[contact]\nplugin = \"hertz_mindlin\"\n" +
                            floor + body;
  const std::string single = simulation(0.01, "[0, 0, -9.81]") +
                             "[material]\nname = \"cake\"\ndensity = 3720\n[contact]\nplugin = \"hertz_mindlin\"\n"
                             "shear_modulus = 10e6\npoisson_ratio = 0.25\nfriction = 0.5\nrestitution = 0.4\n" +
                             floor + body;
  const SceneInstance a = instantiate(load(table), plugins(), {}), b = instantiate(load(single), plugins(), {});
  REQUIRE(a.simulation->dt() == b.simulation->dt());
  a.simulation->run(300);
  b.simulation->run(300);
  const Vec3 x = a.simulation->particles().position[0], y = b.simulation->particles().position[0];
  CHECK(std::memcmp(x.data(), y.data(), sizeof(double) * 3) == 0);
  CHECK(b.simulation->particles().velocity[0].z() > 0);  // it did bounce off the floor
}

TEST_CASE("materials: bad input names file:line, the key and the fix") {
  const std::string head = simulation(0.01, "[0, 0, -9.81]") + kMaterials;
  const std::string chute =
      wall("name = \"chute\"\nshape = \"plane\"\nnormal = [0, 0, 1]\nmaterial = \"steel\"");
  const std::string ok_body = sphere("a", "cake", "[0, 0, 0.01]", "[0, 0, 0]");
  REQUIRE(error_of(head + chute + ok_body).empty());

  SUBCASE("a pair of materials that meet without parameters") {
    // Without the cake-steel row: the cake body can touch the steel chute.
    std::string materials = kMaterials;
    const std::string steel_row = "[[material_pair]]\nmaterials = [\"steel\", \"cake\"]\nfriction = 0.2\nrestitution = 0.7\n";
    REQUIRE(materials.find(steel_row) != std::string::npos);
    materials.erase(materials.find(steel_row), steel_row.size());
    const std::string e = error_of(simulation(0.01, "[0, 0, -9.81]") + materials + chute + ok_body);
    CHECK(e == "materials.toml:40:12: no [[material_pair]] gives friction [1] for materials 'cake' and 'steel', which "
               "meet (body 'a' of 'cake' can touch wall 'chute' of 'steel'); add a row [[material_pair]] materials = "
               "[\"cake\", \"steel\"] with friction = ..., or a default row materials = [\"*\", \"*\"] "
               "(docs/reference/materials.md)");
  }
  SUBCASE("a default row fills every pair") {
    const std::string fallback = "\n[[material_pair]]\nmaterials = [\"*\", \"*\"]\nfriction = 0.3\nrestitution = 0.5\n";
    CHECK(error_of(head + fallback + chute + sphere("r", "rubber", "[0, 0, 0.01]", "[0, 0, 0]")) ==
          "materials.toml:53:12: [[body]] 'r' is of material 'rubber', which has no density; add density = ... "
          "[kg/m^3] to its [[material]] at materials.toml:12:1");
  }
  SUBCASE("an unknown material on a body and on a wall") {
    const std::string e = error_of(head + chute + sphere("a", "stel", "[0, 0, 0.01]", "[0, 0, 0]"));
    CHECK(contains(e, "[[body]] 'a' names material 'stel', which is no [[material]] (did you mean 'steel'?)"));
    CHECK(contains(e, "materials.toml:"));
    const std::string w = error_of(head +
                                   wall("name = \"chute\"\nshape = \"plane\"\nnormal = [0, 0, 1]\nmaterial = \"rubbr\"") +
                                   ok_body);
    CHECK(contains(w, "[[wall]] 'chute' names material 'rubbr', which is no [[material]] (did you mean 'rubber'?)"));
  }
  SUBCASE("a wall or body naming no material among several") {
    const std::string e = error_of(head + wall("name = \"floor\"\nshape = \"plane\"\nnormal = [0, 0, 1]") + ok_body);
    CHECK(contains(e, "[[wall]] 'floor' names no material, and the scene has 3 ('cake', 'rubber', 'steel')"));
  }
  SUBCASE("a law parameter in the wrong place") {
    const std::string in_contact = simulation(0.01, "[0, 0, -9.81]") + kMaterials + "friction = 0.4\n" + chute + ok_body;
    CHECK(contains(error_of(in_contact), "[contact] friction is given per pair of materials in a scene with "
                                         "[[material]] entries (docs/reference/materials.md): move it to [[material_pair]]"));
    const std::string missing = simulation(0.01, "[0, 0, -9.81]") +
                                "[[material]]\nname = \"cake\"\ndensity = 3720\nshear_modulus = 10e6\n"
                                "[contact]\nplugin = \"hertz_mindlin\"\n" + chute + ok_body;
    CHECK(contains(error_of(missing), "[[material]] 'cake' has no poisson_ratio [1], which hertz_mindlin takes per "
                                      "material"));
    const std::string friction_in_material = simulation(0.01, "[0, 0, -9.81]") +
                                             "[[material]]\nname = \"cake\"\ndensity = 3720\nshear_modulus = 10e6\n"
                                             "poisson_ratio = 0.25\nfriction = 0.3\n[contact]\nplugin = \"hertz_mindlin\"\n" +
                                             chute + ok_body;
    CHECK(contains(error_of(friction_in_material),
                   "[material] friction is given per pair of materials for hertz_mindlin (docs/reference/materials.md): move it "
                   "to [[material_pair]]"));
  }
  SUBCASE("a body outside every wall's reach") {
    // Below the floor, dropping away from it (with a small upward speed that cannot lift it back).
    const std::string e = error_of(head + chute + sphere("lost", "cake", "[0, 0, -0.05]", "[0, 0, 0.5]"));
    CHECK(contains(e, "materials.toml:"));
    CHECK(contains(e, "[[body]] 'lost' can never meet a wall: it reaches at most -0.03526 m up"));
    CHECK(contains(e, "the lowest, wall 'chute', reaches 0 m"));
    // Fast enough upwards to reach the floor's level: accepted.
    CHECK(error_of(head + chute + sphere("thrown", "cake", "[0, 0, -0.05]", "[0, 0, 1.1]")).empty());
    // A tilted plane reaches down without end: every body can meet it.
    CHECK(error_of(head + wall("name = \"chute\"\nshape = \"plane\"\nnormal = [0.1, 0, 1]\nmaterial = \"steel\"") +
                   sphere("lost", "cake", "[0, 0, -0.05]", "[0, 0, 0]"))
              .empty());
  }
}

TEST_CASE("material indices go through the run file, the checkpoint and a restart; the resumed run ends alike") {
  // Two bonded bars, one of cake and one of a denser, stiffer 'chalk', dropped on a steel floor.
  const std::string bar_generator =
      "[body.generator]\nplugin = \"box_fill\"\nmin_corner = [0, 0, 0]\nmax_corner = [0.04, 0.008, 0.008]\n"
      "diameter_min = 0.004\ndiameter_max = 0.004\nlattice = \"cubic\"\ngap = 0.3\n";
  const std::string text =
      simulation(0.008, "[0, 0, -9.81]") +
      "[output]\nframe_interval = 0.002\n"
      "[[material]]\nname = \"cake\"\ndensity = 3720\nshear_modulus = 10e6\npoisson_ratio = 0.25\n"
      "[[material]]\nname = \"chalk\"\ndensity = 5000\nshear_modulus = 30e6\npoisson_ratio = 0.2\n"
      "[[material]]\nname = \"steel\"\nshear_modulus = 79e9\npoisson_ratio = 0.3\n"
      "[[material_pair]]\nmaterials = [\"*\", \"*\"]\nfriction = 0.6\nrestitution = 0.5\n"
      "[[material_pair]]\nmaterials = [\"chalk\", \"steel\"]\nfriction = 0.2\n"
      "[contact]\nplugin = \"hertz_mindlin\"\n"
      "[bond]\nplugin = \"beam_bond\"\nyoungs_modulus = 12.8e6\ncritical_stress = 0.24e6\n" +
      wall("name = \"floor\"\nshape = \"plane\"\nnormal = [0, 0, 1]\nmaterial = \"steel\"") +
      "\n[[body]]\nname = \"cake_bar\"\nmaterial = \"cake\"\nposition = [0, 0, 0.01]\nvelocity = [0, 0, -3]\n" +
      bar_generator + "\n[[body]]\nname = \"chalk_bar\"\nmaterial = \"chalk\"\nposition = [0, 0.05, 0.01]\n"
      "velocity = [0, 0, -3]\n" + bar_generator;
  const auto dir = std::filesystem::temp_directory_path() / "shard_test_materials_restart";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bars.toml") << text;
  std::ostringstream log;
  RunOptions reference;
  reference.scene = dir / "bars.toml";
  reference.out_dir = dir / "reference";
  reference.quiet = true;
  const RunSummary whole = run_scene(reference, log);
  REQUIRE(whole.particles == 80);

  RunOptions first = reference;
  first.out_dir = dir / "interrupted";
  first.interrupt_at_step = whole.steps / 2;
  REQUIRE(run_scene(first, log).interrupted());
  const Checkpoint c = read_checkpoint(dir / "interrupted" / "run.checkpoint.h5");
  REQUIRE(c.simulation.particles.material.size() == 80);
  for (std::size_t k = 0; k < 80; ++k) {
    CHECK(c.simulation.particles.material[k] == c.simulation.particles.body[k]);  // cake 0 = body 0, chalk 1 = body 1
    // Each body's density is its material's.
    const double r = c.simulation.particles.radius[k];
    const double rho = c.simulation.particles.mass[k] / (4.0 / 3.0 * std::numbers::pi * r * r * r);
    CHECK(rho == doctest::Approx(c.simulation.particles.material[k] == 0 ? 3720.0 : 5000.0).epsilon(1e-12));
  }
  RunOptions second = reference;
  second.scene.clear();
  second.out_dir = dir / "interrupted";
  second.restart = dir / "interrupted" / "run.h5";
  const RunSummary resumed = run_scene(second, log);
  CHECK(resumed.bonds_broken == whole.bonds_broken);
  const RunFile a(dir / "reference" / "run.h5"), b(dir / "interrupted" / "run.h5");
  REQUIRE(a.frame_count() == b.frame_count());
  for (std::size_t k = 0; k < a.frame_count(); ++k) {
    const FrameData fa = a.read_frame(k), fb = b.read_frame(k);
    CHECK(fa.material == fb.material);
    CHECK(fa.material == fa.body);
    CHECK(fa.position == fb.position);
  }
}
