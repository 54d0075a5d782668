// The load rule (shard/analysis/load_curve.hpp): the loading walls' force along the loading
// direction, negated and summed (the specimen pushes back against the pins' motion), and their
// mean displacement along it.
#include <doctest/doctest.h>

#include "shard/analysis/load_curve.hpp"

using shard::Vec3;
using shard::analysis::PinReading;

TEST_CASE("two pins pressing down: the load is the sum of their reactions, the displacement their mean") {
  PinReading pins(-Vec3::UnitZ());
  // The specimen pushes the pins up (+z) while they travel down (-z); sideways parts do not count.
  pins.add_wall(Vec3(0.5, 0, 3.0), Vec3(0, 0.1, -2e-4));
  pins.add_wall(Vec3(-0.5, 0, 5.0), Vec3(0, 0, -4e-4));
  CHECK(pins.force() == 8.0);
  CHECK(pins.displacement() == doctest::Approx(3e-4).epsilon(1e-15));
}

TEST_CASE("without loading walls the reading is zero") {
  const PinReading none(Vec3::UnitX());
  CHECK(none.force() == 0.0);
  CHECK(none.displacement() == 0.0);
}
