#pragma once
// A scene key set from code instead of the scene file: "section.key" (or "wall.NAME.key") with a
// typed value. Code that varies a scene (the measurement loop, calibration) builds these from
// its numbers, so a value reaches the scene exactly, not through printed text; `shard run --set
// section.key=value` is parsed into one with TOML's rules (a bare word is a string).
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "shard/types.hpp"

namespace shard {

struct SceneOverride {
  using Value = std::variant<bool, std::int64_t, double, std::string, Vec3, std::vector<double>,
                             std::vector<std::string>>;
  // Both always: a lone "section.key=value" string is no key (parse it).
  SceneOverride(std::string key_, Value value_) : key(std::move(key_)), value(std::move(value_)) {}
  // "section.key", "wall.NAME.key", "body.NAME[.generator|.stream].key", "material.NAME.key" or
  // "material_pair.A.B.key" (A = B = "*": the default row); docs/reference/materials.md, "Overrides".
  std::string key;
  Value value;

  // "section.key=value" as --set takes it; throws SceneError naming the assignment when malformed.
  static SceneOverride parse(const std::string& assignment);
  // "section.key=value" again, for messages and logs.
  std::string text() const;
};

using SceneOverrides = std::vector<SceneOverride>;

// Every assignment parsed (--set strings at the command line's boundary).
SceneOverrides parse_overrides(const std::vector<std::string>& assignments);

// A scene key's dot-separated parts: "material_pair.beam.support.friction" -> 4 parts.
std::vector<std::string> scene_key_parts(const std::string& key);

}  // namespace shard
