#pragma once
// Which specimens of a set gave a four-point bending strength. The bending stress is uniform only
// between the loading pins, so a standard's strength counts a fracture there (ASTM C1161, EN 843-1
// report a fracture outside the inner span apart): a specimen that broke outside the pins, or that
// has no crack recorded and did not break apart (it slid off its supports, say), measured
// something else, and a contrast built on it describes the fixture, not the material. A crack
// recorded between the pins with one fragment is valid: a cohesive specimen cracks and hangs
// together.
#include <cstddef>
#include <string>
#include <vector>

#include "shard/measure/measurements.hpp"

namespace shard::measure {

struct InvalidFracture {
  std::string specimen;  // its id
  std::string reason;    // in the lab's words, with the figures that decided
};

struct FractureValidity {
  std::size_t specimens = 0;
  std::vector<InvalidFracture> invalid;
  // Half the set or more: its mean is not a bending test's, and no effect is named from it.
  bool set_invalid() const { return specimens > 0 && 2 * invalid.size() >= specimens; }
};

// The crack is outside the inner span when it lies farther from the centre than half the pin
// distance by more than the crack position is known to: the larger of the set's reported grain
// size and crack position uncertainty. One fragment counts against a specimen only when it has no
// crack position; a specimen with neither record is not judged.
FractureValidity fracture_validity(const MeasurementSet& set);

}  // namespace shard::measure
