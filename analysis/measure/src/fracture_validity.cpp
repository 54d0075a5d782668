#include "shard/measure/fracture_validity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace shard::measure {

FractureValidity fracture_validity(const MeasurementSet& set) {
  FractureValidity v;
  v.specimens = set.specimens.size();
  const double known_to = std::max(set.metadata.test.grain_size, set.metadata.crack_position_uncertainty);
  for (const Specimen& s : set.specimens) {
    // A recorded crack with one fragment is a cohesive specimen that cracked and hangs together.
    if (!s.crack_position && s.fragment_count && *s.fragment_count < 2) {
      v.invalid.push_back({s.id, fmt::format("has no crack recorded and did not break apart ({:g} fragment after the "
                                             "test)",
                                             *s.fragment_count)});
      continue;
    }
    const double half_inner = 0.5 * s.pin_distance;
    if (s.crack_position && std::abs(*s.crack_position) > half_inner + known_to)
      v.invalid.push_back({s.id, fmt::format("broke {:.1f} mm from the centre, outside the inner span (pins at "
                                             "+-{:.1f} mm, crack position known to {:.1f} mm)",
                                             std::abs(*s.crack_position) * 1e3, half_inner * 1e3, known_to * 1e3)});
  }
  return v;
}

}  // namespace shard::measure
