#pragma once
// Unbreakable zones at walls ([[wall]] unbreakable_zone): the bonds between grains that a roller or
// pin presses on never fail. On a coarse packing a line load bears on one or two grains, and their
// bonds crush under it long before the specimen cracks, where a lab's finer material spreads the
// same load over many grains (docs/explanation/four-point-bending.md, "Crushing under the rollers").
#include <cstddef>
#include <vector>

#include "shard/particles.hpp"
#include "shard/wall.hpp"

namespace shard {

// Sets kUnbreakable (particles.hpp) on every particle whose centre lies within a wall's
// unbreakable_zone of its surface (walls without a zone mark nothing); returns the particles each
// wall marked.
std::vector<std::size_t> mark_unbreakable_zones(Particles& particles, const std::vector<Wall>& walls);

}  // namespace shard
