// Which specimens gave a four-point bending strength: a fracture between the pins, known to the
// larger of the grain size and the crack position's uncertainty; a specimen broken outside them
// or not broken apart gave none; a set is invalid when half of it or more gave none.
#include <doctest/doctest.h>

#include "shard/measure/fracture_validity.hpp"

namespace shard::measure {
namespace {

Specimen specimen(const std::string& id, std::optional<double> crack, std::optional<double> fragments) {
  Specimen s;
  s.id = id;
  s.span = 0.17, s.pin_distance = 0.08;
  s.crack_position = crack;
  s.fragment_count = fragments;
  return s;
}

}  // namespace

TEST_CASE("a fracture counts when it lies between the pins, to within what its position is known to") {
  MeasurementSet set;
  set.specimens = {specimen("inside", 0.034, 11), specimen("beside the pin", -0.0445, 9),
                   specimen("over the support", 0.0784, 2), specimen("unrecorded", std::nullopt, std::nullopt)};
  set.metadata.test.grain_size = 3.9e-3;  // the pin at 40 mm: a crack to 43.9 mm is between the pins
  FractureValidity v = fracture_validity(set);
  CHECK(v.specimens == 4);
  REQUIRE(v.invalid.size() == 2);
  CHECK(v.invalid[0].specimen == "beside the pin");
  CHECK(v.invalid[0].reason == "broke 44.5 mm from the centre, outside the inner span (pins at +-40.0 mm, crack "
                               "position known to 3.9 mm)");
  CHECK(v.invalid[1].specimen == "over the support");
  CHECK(v.set_invalid());  // two of four

  set.metadata.crack_position_uncertainty = 5e-3;  // the lab knows the position to 5 mm only
  v = fracture_validity(set);
  REQUIRE(v.invalid.size() == 1);
  CHECK(v.invalid[0].specimen == "over the support");
  CHECK_FALSE(v.set_invalid());
}

TEST_CASE("a specimen with no crack that did not break apart gave no strength; a cracked one that hangs together did") {
  MeasurementSet set;
  set.specimens = {specimen("slid off", std::nullopt, 1), specimen("cohesive", 0.02, 1), specimen("broken", 0.02, 2),
                   specimen("broken too", -0.01, 14)};
  const FractureValidity v = fracture_validity(set);
  REQUIRE(v.invalid.size() == 1);
  CHECK(v.invalid[0].specimen == "slid off");
  CHECK(v.invalid[0].reason == "has no crack recorded and did not break apart (1 fragment after the test)");
  CHECK_FALSE(v.set_invalid());
  CHECK_FALSE(fracture_validity(MeasurementSet{}).set_invalid());
}

}  // namespace shard::measure
