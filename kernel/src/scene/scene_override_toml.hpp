#pragma once
// Applies a typed override to the parsed scene table (scene_override.cpp).
#include <toml++/toml.h>

#include "shard/scene_override.hpp"

namespace shard {

void apply_override(toml::table& root, const SceneOverride& o);

}  // namespace shard
