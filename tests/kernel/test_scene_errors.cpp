#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "kernel_fixtures.hpp"
#include "shard/scene.hpp"

using namespace shard;

namespace {

const std::string kGood = R"(# a small box of spheres on a floor
[simulation]
duration = 0.01
dt = "auto"
seed = 3
gravity = [0, 0, -9.81]

[material]
density = 2500

[generator]
plugin = "box_fill"
min_corner = [0, 0, 0]
max_corner = [0.02, 0.02, 0.02]
diameter_min = 0.004
diameter_max = 0.004
lattice = "cubic"

[contact]
plugin = "linear_spring"
normal_stiffness = 1e4

[[wall]]
name = "floor"
shape = "plane"
point = [0, 0, 0]
normal = [0, 0, 1]
)";

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    load_scene_text(text, "scene.toml", overrides, test::plugins());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("a valid scene loads, and --set overrides reach the plugin parameters") {
  CHECK(error_of(kGood).empty());
  const Scene s = load_scene_text(kGood, "scene.toml", {"contact.normal_stiffness=2e4", "simulation.seed=9"},
                                  test::plugins());
  CHECK(s.contact->params.number("normal_stiffness") == 2e4);
  CHECK(s.seed == 9);
  const bool stored = s.resolved_text.find("20000") != std::string::npos;
  CHECK(stored);
}

TEST_CASE("scene errors name the file, line, column and key, with a hint") {
  // TOML syntax error: line 3 has no value.
  CHECK(error_of(replace(kGood, "duration = 0.01", "duration = ")).find("scene.toml:3:") != std::string::npos);
  // Misspelt kernel key.
  const auto misspelt = error_of(replace(kGood, "duration = 0.01", "duration = 0.01\ngravty = [0, 0, 0]"));
  CHECK(misspelt.find("scene.toml:4:1") != std::string::npos);
  CHECK(misspelt.find("did you mean 'gravity'") != std::string::npos);
  // Misspelt plugin parameter.
  const auto param = error_of(replace(kGood, "normal_stiffness = 1e4", "normal_stifness = 1e4"));
  CHECK(param.find("scene.toml:21:") != std::string::npos);
  CHECK(param.find("did you mean 'normal_stiffness'") != std::string::npos);
  // Wrong type.
  CHECK(error_of(replace(kGood, "normal_stiffness = 1e4", "normal_stiffness = \"stiff\"")).find("must be a number") !=
        std::string::npos);
  // Out of range.
  CHECK(error_of(replace(kGood, "normal_stiffness = 1e4", "normal_stiffness = -5")).find("out of range") !=
        std::string::npos);
  CHECK(error_of(replace(kGood, "density = 2500", "density = -1")).find("[material] density") != std::string::npos);
  // Unknown plugin.
  CHECK(error_of(replace(kGood, "\"linear_spring\"", "\"linear_sprng\"")).find("did you mean 'linear_spring'") !=
        std::string::npos);
  // Unknown section.
  CHECK(error_of(kGood + "\n[contcat]\nx = 1\n").find("did you mean 'contact'") != std::string::npos);
  // Wall shape and a missing mesh file.
  CHECK(error_of(replace(kGood, "shape = \"plane\"", "shape = \"plain\"")).find("is not a wall shape") !=
        std::string::npos);
  const auto missing = error_of(replace(kGood, "shape = \"plane\"", "shape = \"mesh\"\nfile = \"nowhere.stl\""));
  CHECK(missing.find("nowhere.stl") != std::string::npos);
  // Missing required section and value.
  CHECK(error_of(replace(kGood, "duration = 0.01", "")).find("duration") != std::string::npos);
  // A stop rule that names a wall that does not exist.
  CHECK(error_of(kGood + "\n[stop]\nload_walls = [\"flor\"]\n").find("did you mean 'floor'") != std::string::npos);
  // A malformed --set.
  CHECK(error_of(kGood, {"contact.normal_stiffness"}).find("expected section.key=value") != std::string::npos);
  // A bad value given by --set is located at the override, not at a line of the file.
  const auto set_word = error_of(kGood, {"contact.normal_stiffness=stiff"});
  CHECK(set_word.find("scene.toml (a value given by --set, not in the file): ") == 0);
  CHECK(set_word.find("normal_stiffness") != std::string::npos);
  const auto set_misspelt = error_of(kGood, {"contact.normal_stifness=2e4"});
  CHECK(set_misspelt.find(":0:0") == std::string::npos);
  CHECK(set_misspelt.find("did you mean 'normal_stiffness'") != std::string::npos);
}

TEST_CASE("a bond plugin's own refusal (an unknown effect policy) names the [bond] section and the valid names") {
  const std::string text = kGood + "\n[bond]\nplugin = \"beam_bond\"\neffects = \"softening, sofening\"\n";
  const Scene scene = load_scene_text(text, "scene.toml", {}, test::plugins());
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(text.find("[bond]")), '\n');
  std::string message;
  try {
    instantiate(scene, test::plugins(), [](const std::string&) {});
  } catch (const SceneError& e) {
    message = e.what();
  }
  CHECK(message.find("scene.toml:" + std::to_string(line) + ":") != std::string::npos);
  CHECK(message.find("[bond]") != std::string::npos);
  CHECK(message.find("'sofening'") != std::string::npos);
  for (const char* name : {"weibull_strength", "softening", "viscosity", "compression_asymmetry"})
    CHECK(message.find(name) != std::string::npos);
}

// toml++ 3.3 reaches undefined behaviour on some non-ASCII code points wherever it tests them for
// blanks; the loader refuses them outside comments, so it must know exactly where a comment is.
TEST_CASE("characters toml++ 3.3 cannot read are refused outside comments, where strings end exactly") {
  const std::string accent = "\xc3\xa9";  // U+00E9
  // In a comment: allowed, also after a string holding an escaped quote.
  CHECK(error_of(replace(kGood, "seed = 3", "seed = 3 # r" + accent + "sum" + accent)).empty());
  CHECK(error_of(replace(kGood, "lattice = \"cubic\"", "lattice = \"cubic\" # \"" + accent)).empty());
  // A '#' inside a string is text, not a comment: a basic string with an escaped quote, a literal
  // string, a multi-line string.
  CHECK(error_of(replace(kGood, "seed = 3", "note = \"a\\\"#" + accent + "\"")).find("U+00E9") != std::string::npos);
  CHECK(error_of(replace(kGood, "seed = 3", "note = 'a#" + accent + "'")).find("U+00E9") != std::string::npos);
  CHECK(error_of(replace(kGood, "seed = 3", "note = \"\"\"a\n#" + accent + "\"\"\"")).find("scene.toml:6:2: the character U+00E9") !=
        std::string::npos);
  // Found by fuzz_scene: four quotes open a multi-line string, so the '#' after them is text and
  // U+FCFF after a backslash reached TOML_UNREACHABLE.
  const std::string fuzz_case = "\"\"\"\"# Sp\\\\\\\\\\\xef\xb3\xbf\\\\\nname = \"a\"\n";
  CHECK(error_of(fuzz_case).find("scene.toml:1:") != std::string::npos);
  CHECK(error_of(fuzz_case).find("U+FCFF") != std::string::npos);
}
