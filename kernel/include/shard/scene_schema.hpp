#pragma once
// The kernel's own scene keys, section by section, with type, unit, default and meaning: what
// `shard schema` prints as the scene reference (docs/reference/scene-format.md) beside the
// plugins' parameter schemas. The loader (kernel/src/scene/) reads the keys; test_scene_schema
// checks that every key it accepts is listed here and every key listed here is accepted.
#include <optional>
#include <string>
#include <vector>

#include "shard/plugin.hpp"

namespace shard {

struct SceneKeySpec {
  std::string name;
  std::string type;     // number, integer, bool, string, vec3, "auto or number", array of strings, table
  std::string unit;     // SI unit, "1" for dimensionless, "" where none applies
  std::string default_text;  // as written in a scene; "required" when the key must be given
  std::string doc;      // one line
};

struct SceneSectionSpec {
  std::string header;  // as written in a scene: "[simulation]", "[[wall]]", "[body.stream]"
  std::string doc;
  std::vector<SceneKeySpec> keys;
  // Sections whose other keys are the parameters of the plugin named by `plugin`, or of the
  // contact law (per material or per pair of materials).
  std::optional<PluginKind> plugin_kind;
};

// In the order a scene usually lists them.
const std::vector<SceneSectionSpec>& scene_schema();

}  // namespace shard
