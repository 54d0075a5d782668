// --set material.NAME.key and material_pair.A.B.key (docs/reference/materials.md, "Overrides"): an override
// changes the physics as the law predicts (the sliding deceleration mu g follows an overridden
// friction, the particle mass an overridden density, the Rayleigh time step an overridden shear
// modulus), a pair without its own row gets one, and bad overrides are refused naming the
// override and the valid names.
#include <doctest/doctest.h>

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sweep_plan.hpp"
#include "../common/installed_plugins.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

using namespace shard;

namespace {

using testing::plugins;

constexpr double kRadius = 0.002, kDensity = 3720, kG = 9.81;  // m, kg/m^3, m/s^2

// Cake spheres on a rubber and a steel cylinder: cake-rubber has its own row (mu 0.3), cake-steel
// takes the default row (mu 0.5); restitution 0.5 everywhere from the default row.
const std::string kScene = R"([simulation]
duration = 0.03
dt = "auto"
gravity = [0, 0, -9.81]

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
materials = ["cake", "rubber"]
friction = 0.3

[[material_pair]]
materials = ["*", "*"]
friction = 0.5
restitution = 0.5

[contact]
plugin = "hertz_mindlin"

[[wall]]
name = "belt"
shape = "cylinder"
point = [0, 0, -0.4]
axis = [1, 0, 0]
radius = 0.4
length = 1
material = "rubber"

[[wall]]
name = "chute"
shape = "cylinder"
point = [0, 1, -0.4]
axis = [1, 0, 0]
radius = 0.4
length = 1
material = "steel"
)";

// One 4 mm cake sphere at `position` moving at 2 m/s along x.
std::string sphere(const std::string& name, double y, double z) {
  return fmt::format(R"(
[[body]]
name = "{}"
material = "cake"
position = [-0.3, {}, {:.17g}]
velocity = [2, 0, 0]
[body.generator]
plugin = "box_fill"
min_corner = [0, 0, 0]
max_corner = [0.004, 0.004, 0.004]
diameter_min = 0.004
diameter_max = 0.004
lattice = "cubic"
)",
                     name, y, z);
}

double e_star(double g1, double nu1, double g2, double nu2) {
  const double e1 = 2 * g1 * (1 + nu1), e2 = 2 * g2 * (1 + nu2);
  return 1.0 / ((1 - nu1 * nu1) / e1 + (1 - nu2 * nu2) / e2);
}

// The scene with a sphere on each cylinder, each at its static Hertz overlap.
std::string sliding_scene() {
  const double m = kDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3);
  const auto seated = [&](double e) { return kRadius - std::pow(m * kG / (4.0 / 3.0 * e * std::sqrt(kRadius)), 2.0 / 3.0); };
  return kScene + sphere("on_belt", 0, seated(e_star(10e6, 0.25, 1e6, 0.45))) +
         sphere("on_chute", 1, seated(e_star(10e6, 0.25, 79e9, 0.3)));
}

Scene load(const std::vector<std::string>& overrides) {
  return load_scene_text(sliding_scene(), "sliding.toml", overrides, plugins());
}

std::string error_of(const std::vector<std::string>& overrides, const std::string& text = sliding_scene()) {
  try {
    load_scene_text(text, "sliding.toml", overrides, plugins());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The x deceleration of each body's sphere over 30 ms of sliding; bodies 0 (rubber), 1 (steel).
std::vector<double> decelerations(const Scene& scene) {
  const SceneInstance inst = instantiate(scene, plugins(), {});
  Simulation& sim = *inst.simulation;
  sim.run(static_cast<std::int64_t>(std::ceil(0.03 / sim.dt())));
  std::vector<double> out(2);
  const auto& p = sim.particles();
  for (std::size_t k = 0; k < p.size(); ++k) {
    CHECK(p.velocity[k].x() - p.omega[k].y() * kRadius > 0.1);  // still sliding
    out[static_cast<std::size_t>(p.body[k])] = (2.0 - p.velocity[k].x()) / sim.time();
  }
  return out;
}

}  // namespace

TEST_CASE("material_pair overrides change the sliding deceleration to the overridden mu g") {
  // Sliding lasts 2 v0 / (7 mu g) >= 58 ms for mu <= 1: still sliding at 30 ms. Each step's Coulomb
  // force is mu F_n on a vertical normal, so the deceleration is mu g to the 0.5 % of
  // test_scene_materials (v_z of the seated sphere stays ~0).
  const std::vector<double> as_written = decelerations(load({}));
  CHECK(as_written[0] == doctest::Approx(0.3 * kG).epsilon(0.005));  // its own row
  CHECK(as_written[1] == doctest::Approx(0.5 * kG).epsilon(0.005));  // the default row

  // The existing row named in the other order; a new row for cake-steel (restitution still from the
  // default row, key by key).
  const Scene overridden = load({"material_pair.rubber.cake.friction=0.8", "material_pair.steel.cake.friction=0.2"});
  CHECK(overridden.material_pairs[0 * 3 + 1].number("friction") == 0.8);
  CHECK(overridden.material_pairs[0 * 3 + 2].number("friction") == 0.2);
  CHECK(overridden.material_pairs[2 * 3 + 0].number("friction") == 0.2);
  CHECK(overridden.material_pairs[0 * 3 + 2].number("restitution") == 0.5);
  const std::vector<double> a = decelerations(overridden);
  MESSAGE("decelerations: as written " << as_written[0] << ", " << as_written[1] << "; overridden " << a[0] << ", "
                                       << a[1] << " m/s^2");
  CHECK(a[0] == doctest::Approx(0.8 * kG).epsilon(0.005));
  CHECK(a[1] == doctest::Approx(0.2 * kG).epsilon(0.005));

  // The default row: cake-steel follows it, cake-rubber keeps its own row.
  const std::vector<double> d = decelerations(load({"material_pair.*.*.friction=0.7"}));
  CHECK(d[0] == doctest::Approx(0.3 * kG).epsilon(0.005));
  CHECK(d[1] == doctest::Approx(0.7 * kG).epsilon(0.005));
}

TEST_CASE("material overrides: density sets the particle mass, shear modulus the Rayleigh time step") {
  const Scene base = load({});
  const Scene heavy = load({"material.cake.density=7440", "material.cake.shear_modulus=40e6"});
  CHECK(heavy.materials[0].density == 7440);
  CHECK(heavy.materials[0].law.number("shear_modulus") == 40e6);
  CHECK(heavy.materials[2].law.number("shear_modulus") == 79e9);  // the others untouched
  const SceneInstance a = instantiate(base, plugins(), {}), b = instantiate(heavy, plugins(), {});
  const double m = kDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3);
  CHECK(a.simulation->particles().mass[0] == doctest::Approx(m).epsilon(1e-12));
  CHECK(b.simulation->particles().mass[0] == doctest::Approx(2 * m).epsilon(1e-12));
  // Rayleigh time pi r sqrt(rho / G) / (0.1631 nu + 0.8766) of the only material with spheres:
  // twice the density and four times G give sqrt(2 / 4) of the step.
  CHECK(b.simulation->dt() / a.simulation->dt() == doctest::Approx(std::sqrt(0.5)).epsilon(1e-12));
}

TEST_CASE("material overrides reach a sweep: --vary material_pair.A.B.key goes through the same override") {
  const std::filesystem::path scene = std::filesystem::path(SHARD_SOURCE_DIR) / "scenes/belt_roller.toml";
  const SweepPlan plan = plan_sweep(scene, {}, parse_vary("material_pair.cake.rubber.friction=0.4,0.9"), plugins());
  CHECK(plan.form == VaryForm::number);
  const Scene s = load_scene(scene, plugins(), run_overrides(plan, {}, 0.4, 0));
  std::size_t cake = 99, rubber = 99;
  for (std::size_t k = 0; k < s.materials.size(); ++k) {
    if (s.materials[k].name == "cake") cake = k;
    if (s.materials[k].name == "rubber") rubber = k;
  }
  REQUIRE(cake < s.materials.size());
  REQUIRE(rubber < s.materials.size());
  CHECK(s.material_pairs[cake * s.materials.size() + rubber].number("friction") == 0.4);
  std::string message;
  try {
    plan_sweep(scene, {}, parse_vary("material.cake.frction=0.4,0.9"), plugins());
  } catch (const SceneError& e) {
    message = e.what();
  }
  CHECK(contains(message, "--vary 'material.cake.frction=0.4,0.9' (value 0.4): --set 'material.cake.frction=0.4': "
                          "unknown key 'frction' for [[material]] 'cake'"));
}

TEST_CASE("bad material overrides are refused naming the override and the valid names") {
  const std::string no_material = error_of({"material.stel.density=7800"});
  CHECK(contains(no_material, "--set 'material.stel.density=7800': no [[material]] named 'stel' (did you mean "
                              "'steel'?); the scene's materials: 'cake', 'rubber', 'steel'"));
  CHECK(contains(error_of({"material_pair.cake.stone.friction=0.3"}),
                 "--set 'material_pair.cake.stone.friction=0.3': no [[material]] named 'stone'; the scene's "
                 "materials: 'cake', 'rubber', 'steel'"));
  CHECK(contains(error_of({"material_pair.*.cake.friction=0.3"}), "name two materials"));
  const std::string unknown = error_of({"material.cake.shear_modulas=1e6"});
  CHECK(contains(unknown, "--set 'material.cake.shear_modulas=1000000': unknown key 'shear_modulas' for "
                          "[[material]] 'cake' (did you mean 'shear_modulus'?); valid keys: density, shear_modulus, "
                          "poisson_ratio"));
  CHECK(contains(error_of({"material_pair.cake.steel.fricton=0.3"}),
                 "unknown key 'fricton' for [[material_pair]] ['cake', 'steel'] (did you mean 'friction'?); valid "
                 "keys: friction, restitution"));
  CHECK(contains(error_of({"material.cake.frction=0.3"}),
                 "unknown key 'frction' for [[material]] 'cake' (did you mean 'material_pair.A.B.friction'?); valid "
                 "keys: density, shear_modulus, poisson_ratio"));
  CHECK(contains(error_of({"material.cake.friction=0.3"}),
                 "--set 'material.cake.friction=0.3': hertz_mindlin takes friction per pair of materials "
                 "(docs/reference/materials.md): set it with --set material_pair.A.B.friction=..."));
  CHECK(contains(error_of({"material_pair.cake.steel.poisson_ratio=0.3"}),
                 "set it with --set material.NAME.poisson_ratio=..."));
  CHECK(contains(error_of({"material.cake.name=\"dough\""}), "'name' names what the other entries refer to"));
  CHECK(contains(error_of({"material_pair.cake.steel.materials=[\"a\", \"b\"]"}),
                 "'materials' names what the other entries refer to"));
  // The single [material] form and the entry form each say how to reach their values.
  CHECK(contains(error_of({"material.density=3000"}),
                 "--set 'material.density=3000': the scene has [[material]] entries; name one: "
                 "material.NAME.density=... (the scene's materials: 'cake', 'rubber', 'steel')"));
  const std::string one = R"([simulation]
duration = 0.01
[material]
density = 3720
[generator]
plugin = "box_fill"
min_corner = [0, 0, 0]
max_corner = [0.004, 0.004, 0.004]
diameter_min = 0.004
diameter_max = 0.004
)";
  CHECK(error_of({"material.density=3000"}, one).empty());
  CHECK(contains(error_of({"material.cake.density=3000"}, one),
                 "the scene has one [material] section, not [[material]] entries: set its density with "
                 "material.density=..."));
  CHECK(contains(error_of({"material_pair.a.b.friction=0.3"}, one), "one [material] section"));
  // A list of entries has no key of its own (this used to write through a null table).
  CHECK(contains(error_of({"wall.friction=0.3"}), "--set 'wall.friction=0.3': [[wall]] is a list of entries; name "
                                                  "one, e.g. wall.NAME.friction=..."));
}
