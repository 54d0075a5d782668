#pragma once
// The materials of a scene (docs/reference/materials.md): the single [material] section, or [[material]]
// entries holding the contact law's per-material parameters and [[material_pair]] rows holding
// its per-pair ones. Bodies and walls name their material; every pair of materials that can meet
// (two bodies' or a body's and a wall's) must have its per-pair parameters, from its own row or
// the default row materials = ["*", "*"].
#include <string>
#include <vector>
#include <toml++/toml.h>

#include "shard/scene.hpp"
#include "shard/scene_override.hpp"

namespace shard::scene_detail {

// The material a wall names, read with the wall (scene_loader.cpp).
struct WallMaterial {
  std::string name;   // empty: none named
  std::string where;  // file:line:column of the key, or of the [[wall]] entry
};

// Fills scene.materials, scene.density, scene.material_table and scene.material_pairs, and the
// material index of every body and wall (`walls` parallel to scene.walls). Needs scene.contact,
// scene.bodies and scene.walls read. Throws SceneError with file:line:column, key and fix.
void read_materials(const toml::table& root, const std::string& file, const PluginHost& host,
                    const std::vector<WallMaterial>& walls, Scene& scene);

// The keys of the --set material.NAME.key and material_pair.A.B.key overrides against the
// contact law's parameters of each table (its names were checked when the override was applied):
// an unknown key, or one of the law's parameters in the wrong table, is refused naming the
// override, the valid keys and where the parameter goes. Needs scene.contact read.
void check_material_overrides(const SceneOverrides& overrides, const PluginHost& host, const Scene& scene);

}  // namespace shard::scene_detail
