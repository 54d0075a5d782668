// `shard calibrate ... --with EFFECT` runs calibrate-effect (with --reference: calibrate-contrast);
// without --with, calibrate stays the bending calibration. `shard diagnose` of two or more
// measurement folders, or with --reference, runs diagnose-sets.
#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "shard/app/command_routing.hpp"

using shard::route_measurement_command;
using Args = std::vector<std::string>;

// A folder name no other test process uses at the same time (ctest -j).
static std::string fmt_unique(const char* stem) { return std::string(stem) + "_" + std::to_string(::getpid()); }

TEST_CASE("calibrate --with is routed to calibrate-effect, nothing else is") {
  Args a{"shard", "calibrate", "meas", "--scene", "s.toml", "--with", "bond_viscosity"};
  CHECK(route_measurement_command(a));
  CHECK(a[1] == "calibrate-effect");
  CHECK(a.size() == 7);

  Args b{"shard", "--plugin-dir", "calibrate", "calibrate", "meas", "--with=machine_compliance"};
  CHECK(route_measurement_command(b));
  CHECK(b[2] == "calibrate");  // the --plugin-dir value is a folder, not the command
  CHECK(b[3] == "calibrate-effect");

  Args c{"shard", "calibrate", "scenes/four_point_bending.toml", "--target-E", "13.2e6"};
  CHECK_FALSE(route_measurement_command(c));
  CHECK(c[1] == "calibrate");

  Args d{"shard", "run", "scene.toml", "--with"};  // another command's argument
  CHECK_FALSE(route_measurement_command(d));
  CHECK(d[1] == "run");

  Args e{"shard", "calibrate", "--", "--with"};  // after "--" it is a positional
  CHECK_FALSE(route_measurement_command(e));
}

TEST_CASE("diagnose of several measurement folders, or with --reference, is the contrast diagnosis") {
  namespace fs = std::filesystem;
  const fs::path top = fs::temp_directory_path() / fmt_unique("shard_routing");
  for (const char* name : {"A", "B"}) {
    fs::create_directories(top / name);
    std::ofstream(top / name / "specimens.csv") << "id\n";
  }
  const std::string a = (top / "A").string(), b = (top / "B").string();
  Args two{"shard", "diagnose", a, b, "--scene", "s.toml"};
  CHECK(route_measurement_command(two));
  CHECK(two[1] == "diagnose-sets");

  Args one{"shard", "diagnose", a, "--scene", "s.toml"};  // one set: the single-set diagnosis
  CHECK_FALSE(route_measurement_command(one));
  CHECK(one[1] == "diagnose");

  Args with_ref{"shard", "diagnose", a, "--reference=A", "--scene", "s.toml"};
  CHECK(route_measurement_command(with_ref));
  CHECK(with_ref[1] == "diagnose-sets");

  Args calibrate{"shard", "calibrate", a, b, "--reference", "A", "--with", "bond_softening"};
  CHECK(route_measurement_command(calibrate));
  CHECK(calibrate[1] == "calibrate-contrast");
  fs::remove_all(top);
}
