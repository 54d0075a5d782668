#pragma once
// The check that every body can meet a wall (docs/reference/materials.md, "Bodies out of reach").
#include <vector>

#include "body_placement.hpp"
#include "shard/scene.hpp"

namespace shard::scene_detail {

// Under gravity, a body whose highest reach -- the top of its spheres plus the rise its upward
// speed allows, (v.u)^2 / 2g -- lies below the lowest point of every wall falls away from all of
// them and can never meet one: throws SceneError naming the body, the heights and the fix. A wall
// that moves (velocity, ramp, table or spin) or reaches down without end (a plane not
// perpendicular to gravity) is within every body's reach. No gravity or no walls: no check.
void check_bodies_reach_walls(const PlacedBodies& placed, const std::vector<BodySpec>& specs,
                              const std::vector<Wall>& walls, const Vec3& gravity);

}  // namespace shard::scene_detail
