#pragma once
// The bodies of a scene: the single [generator] section (one body, placed as generated) or
// [[body]] entries, each with a [body.generator] and an optional [body.stream] (docs/reference/bodies.md).
#include <string>
#include <vector>
#include <toml++/toml.h>

#include "shard/scene.hpp"

namespace shard::scene_detail {

// Throws SceneError with file:line:column and the key for a missing or doubled form, unknown
// keys, a non-unit stream, and the generator plugin's own parameter errors.
std::vector<BodySpec> read_bodies(const toml::table& root, const std::string& file, const PluginHost& host);

}  // namespace shard::scene_detail
