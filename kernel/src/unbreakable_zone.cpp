#include "shard/unbreakable_zone.hpp"

namespace shard {

std::vector<std::size_t> mark_unbreakable_zones(Particles& particles, const std::vector<Wall>& walls) {
  std::vector<std::size_t> marked(walls.size(), 0);
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const double zone = walls[w].unbreakable_zone;
    if (!(zone > 0)) continue;
    for (std::size_t k = 0; k < particles.size(); ++k) {
      Vec3 normal;
      double distance = 0;
      if (!wall_contact(walls[w], particles.position[k], zone, normal, distance) || distance > zone) continue;
      ++marked[w];
      particles.flags[k] |= kUnbreakable;
    }
  }
  return marked;
}

}  // namespace shard
