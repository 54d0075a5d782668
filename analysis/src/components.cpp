#include "shard/analysis/components.hpp"

#include <limits>
#include <stdexcept>
#include <string>

namespace shard::analysis {


void check_bonds(std::size_t particle_count, const BondList& bonds) {
  if (bonds.i.size() != bonds.j.size()) {
    throw std::invalid_argument("bond arrays differ in length: " + std::to_string(bonds.i.size()) +
                                " vs " + std::to_string(bonds.j.size()));
  }
  if (particle_count > static_cast<std::size_t>(std::numeric_limits<Index>::max())) {
    throw std::invalid_argument("too many particles for 32-bit indices");
  }
  const auto n = static_cast<Index>(particle_count);
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    if (bonds.i[k] < 0 || bonds.i[k] >= n || bonds.j[k] < 0 || bonds.j[k] >= n) {
      throw std::invalid_argument("bond " + std::to_string(k) + " (" + std::to_string(bonds.i[k]) +
                                  ", " + std::to_string(bonds.j[k]) +
                                  ") refers to a particle outside [0, " + std::to_string(n) + ")");
    }
  }
}

}  // namespace shard::analysis
