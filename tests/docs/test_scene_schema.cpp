// The kernel's scene schema (shard/scene_schema.hpp), which `shard schema` prints as the scene
// reference, against the scene loader: for every section the loader reads itself, the keys it
// accepts (the "valid keys" of its unknown-key error) are exactly the keys the schema lists.
#include <doctest/doctest.h>

#include <set>
#include <sstream>
#include <string>

#include "../common/installed_plugins.hpp"
#include "shard/scene.hpp"
#include "shard/scene_schema.hpp"

using namespace shard;
using shard::testing::plugins;

namespace {

const std::string kSimulation = "[simulation]\nduration = 0.01\n";
const std::string kMaterial = "[material]\ndensity = 1000\n";
const std::string kBoxFill =
    "plugin = \"box_fill\"\nmin_corner = [0, 0, 0]\nmax_corner = [0.01, 0.01, 0.01]\n"
    "diameter_min = 0.002\ndiameter_max = 0.002\n";
const std::string kGenerator = "[generator]\n" + kBoxFill;
const std::string kUnknown = "zz_not_a_key = 1\n";

// A key set as one line, so a failing CHECK prints both lists.
std::string joined(const std::set<std::string>& keys) {
  std::string out;
  for (const auto& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
}

// The keys the loader lists when it refuses an unknown key in `text`.
std::set<std::string> accepted_keys(const std::string& text) {
  try {
    load_scene_text(text, "schema.toml", {}, plugins());
  } catch (const SceneError& e) {
    const std::string message = e.what();
    const auto at = message.find("valid keys: ");
    REQUIRE_MESSAGE(at != std::string::npos, message);
    std::set<std::string> keys;
    std::istringstream list(message.substr(at + 12));
    for (std::string key; std::getline(list, key, ',');) keys.insert(key.substr(key.find_first_not_of(' ')));
    return keys;
  }
  FAIL("the scene with an unknown key loaded:\n" << text);
  return {};
}

std::set<std::string> schema_key_set(const std::string& header) {
  for (const auto& section : scene_schema())
    if (section.header == header) {
      std::set<std::string> keys;
      for (const auto& k : section.keys) keys.insert(k.name);
      return keys;
    }
  FAIL("no section " << header << " in the scene schema");
  return {};
}

std::string schema_keys(const std::string& header) { return joined(schema_key_set(header)); }
std::string loader_keys(const std::string& text) { return joined(accepted_keys(text)); }

std::string wall(const std::string& shape_keys) {
  return "[[wall]]\nname = \"w\"\n" + shape_keys + kUnknown;
}

}  // namespace

TEST_CASE("the scene schema lists exactly the keys the loader accepts") {
  const std::string base = kSimulation + kMaterial + kGenerator;
  CHECK(loader_keys(kSimulation + kUnknown + kMaterial + kGenerator) == schema_keys("[simulation]"));
  CHECK(loader_keys(kSimulation + kMaterial + kUnknown + kGenerator) == schema_keys("[material]"));
  CHECK(loader_keys(base + "[output]\n" + kUnknown) == schema_keys("[output]"));
  CHECK(loader_keys(base + "[analysis]\n" + kUnknown) == schema_keys("[analysis]"));
  CHECK(loader_keys(base + "[stop]\n" + kUnknown) == schema_keys("[stop]"));
  CHECK(loader_keys(base + "[[grip]]\nmin_corner = [0, 0, 0]\nmax_corner = [1, 1, 1]\n" + kUnknown) ==
        schema_keys("[[grip]]"));
  // A wall reads the keys of its shape: together the three shapes' keys are the section's.
  std::set<std::string> walls = accepted_keys(base + wall("shape = \"plane\"\n"));
  walls.merge(accepted_keys(base + wall("shape = \"cylinder\"\nradius = 0.01\nlength = 0.1\n")));
  walls.merge(accepted_keys(base + wall("shape = \"mesh\"\nfile = \"" SHARD_SOURCE_DIR "/scenes/geometry/cube_10mm.stl\"\n")));
  CHECK(joined(walls) == schema_keys("[[wall]]"));
  const std::string body = kSimulation + kMaterial + "[[body]]\nname = \"b\"\n";
  CHECK(loader_keys(body + kUnknown + "[body.generator]\n" + kBoxFill) == schema_keys("[[body]]"));
  CHECK(loader_keys(body + "[body.generator]\n" + kBoxFill + "[body.stream]\ncopies = 1\nstart = [0, 0, 0]\n" +
                      kUnknown) == schema_keys("[body.stream]"));
}

TEST_CASE("every key of the scene schema has a type and a meaning, and no section lists a key twice") {
  for (const auto& section : scene_schema()) {
    std::set<std::string> seen;
    for (const auto& k : section.keys) {
      CAPTURE(section.header);
      CAPTURE(k.name);
      CHECK(seen.insert(k.name).second);
      CHECK_FALSE(k.type.empty());
      CHECK_FALSE(k.doc.empty());
      CHECK_FALSE(k.default_text.empty());
    }
  }
}
