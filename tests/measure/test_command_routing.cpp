// `shard calibrate ... --with EFFECT` runs calibrate-effect; without --with, calibrate stays the
// bending calibration.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "shard/app/command_routing.hpp"

using shard::route_calibrate_with;
using Args = std::vector<std::string>;

TEST_CASE("calibrate --with is routed to calibrate-effect, nothing else is") {
  Args a{"shard", "calibrate", "meas", "--scene", "s.toml", "--with", "bond_viscosity"};
  CHECK(route_calibrate_with(a));
  CHECK(a[1] == "calibrate-effect");
  CHECK(a.size() == 7);

  Args b{"shard", "--plugin-dir", "calibrate", "calibrate", "meas", "--with=machine_compliance"};
  CHECK(route_calibrate_with(b));
  CHECK(b[2] == "calibrate");  // the --plugin-dir value is a folder, not the command
  CHECK(b[3] == "calibrate-effect");

  Args c{"shard", "calibrate", "scenes/four_point_bending.toml", "--target-E", "13.2e6"};
  CHECK_FALSE(route_calibrate_with(c));
  CHECK(c[1] == "calibrate");

  Args d{"shard", "run", "scene.toml", "--with"};  // another command's argument
  CHECK_FALSE(route_calibrate_with(d));
  CHECK(d[1] == "run");

  Args e{"shard", "calibrate", "--", "--with"};  // after "--" it is a positional
  CHECK_FALSE(route_calibrate_with(e));
}
