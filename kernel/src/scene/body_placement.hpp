#pragma once
// Rigid placement of generated packings as the bodies of a scene, and the check that bodies do
// not overlap as placed (scene_instance.cpp builds the particles from it).
#include <cstdint>
#include <string>
#include <vector>

#include "shard/generator.hpp"
#include "shard/scene.hpp"

namespace shard::scene_detail {

// Every particle of every body, as placed.
struct PlacedBodies {
  GeneratedBody all;  // positions, radii, materials, bonds (row pairs into all)
  std::vector<Vec3> velocity, omega;
  std::vector<std::int32_t> body;       // body id per particle
  std::vector<std::string> body_names;  // per body id
  std::vector<std::size_t> spec_of;     // per body id: index of its BodySpec
};

// Centre of mass of a packing of equal-density spheres (weights r^3).
Vec3 centre_of_mass(const GeneratedBody& packing);

// Places every copy of `spec` (one, or a stream's) from its packing; bodies get consecutive ids.
void place_body(const BodySpec& spec, std::size_t spec_index, const GeneratedBody& packing, PlacedBodies& out);

// Throws SceneError naming both bodies (entry and copy), the overlap and the fix when particles
// of different bodies overlap by more than kBodyOverlapTolerance of the smaller radius.
void check_body_overlaps(const PlacedBodies& placed, const std::vector<BodySpec>& specs);

}  // namespace shard::scene_detail
