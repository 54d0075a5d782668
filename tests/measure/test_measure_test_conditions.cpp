// How the lab ran its tests (metadata.toml [test], [notes]): read, written back, applied to the
// curves (zero offset subtracted, curves zeroed at the seating preload), and unknown keys named.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "shard/measure/measurement_error.hpp"
#include "shard/measure/measurements.hpp"

namespace fs = std::filesystem;
using namespace shard::measure;

namespace {

void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

const char* kSpecimens =
    "id,length,width,height,span,pin_distance,loading_rate\n"
    "A,0.18,0.03,0.035,0.17,0.08,0.02\n";
const char* kCurve = "time,displacement,force\n0,0,0.53\n1,1e-5,2.03\n2,2e-5,4.03\n3,3e-5,5.53\n4,4e-5,3.03\n";

fs::path folder(const std::string& name, const std::string& metadata) {
  const fs::path dir = fs::temp_directory_path() / ("shard_test_conditions_" + name);
  fs::remove_all(dir);
  write(dir / "metadata.toml", metadata);
  write(dir / "specimens.csv", kSpecimens);
  write(dir / "curves/A.csv", kCurve);
  return dir;
}

std::string error_of(const std::string& metadata) {
  try {
    read_measurements(folder("bad", metadata));
  } catch (const MeasurementError& e) {
    return e.what();
  }
  FAIL("the reader accepted a bad metadata.toml");
  return "";
}

const std::string kLab = R"(name = "four-point bending, span 170 mm"

[uncertainty]
load_cell = 0.05
displacement = 1e-6

[test]
seating_preload = 0.5
zero_offset = 0.03
ramp = "1-cos"
ramp_time = 0.025
grain_size = 8e-4
fragment_size_threshold = 1e-3
notes = "pins 80 mm apart at 20 mm/s"

[notes]
operator = "A. N. Other"
batch = "3, dried 24 h"
machine = { make = "Zwick", cell = "50 N" }
)";

}  // namespace

TEST_CASE("[test] carries preload, zero offset, ramp, grain size, fragment threshold and notes; [notes] anything") {
  const MeasurementSet set = read_measurements(folder("lab", kLab));
  const TestConditions& t = set.metadata.test;
  CHECK(t.seating_preload == 0.5);
  CHECK(t.zero_offset == 0.03);
  CHECK(t.ramp == "1-cos");
  CHECK(t.ramp_time == 0.025);
  CHECK(t.grain_size == 8e-4);
  CHECK(t.fragment_size_threshold == 1e-3);
  CHECK(t.notes == "pins 80 mm apart at 20 mm/s");
  CHECK(set.metadata.notes.find("Zwick") != std::string::npos);  // kept, not interpreted
  CHECK(set.metadata.notes.find("dried 24 h") != std::string::npos);
  // The known zero offset is subtracted from every force read: 0.53 N read is 0.5 N of load.
  const Curve& c = set.specimens[0].curve;
  CHECK(c.force[0] == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(c.force[3] == doctest::Approx(5.5).epsilon(1e-15));

  // Written and read back: the same conditions (and the same forces once the offset is re-added).
  MeasurementSet copy = set;
  for (double& f : copy.specimens[0].curve.force) f += t.zero_offset;
  const fs::path out = fs::temp_directory_path() / "shard_test_conditions_written";
  fs::remove_all(out);
  write_measurements(copy, out);
  const MeasurementSet back = read_measurements(out);
  CHECK(back.metadata.test.seating_preload == 0.5);
  CHECK(back.metadata.test.zero_offset == 0.03);
  CHECK(back.metadata.test.ramp == "1-cos");
  CHECK(back.metadata.test.ramp_time == 0.025);
  CHECK(back.metadata.test.grain_size == 8e-4);
  CHECK(back.metadata.test.fragment_size_threshold == 1e-3);
  CHECK(back.metadata.test.notes == t.notes);
  CHECK(back.metadata.notes == set.metadata.notes);
  CHECK(back.specimens[0].curve.force[3] == doctest::Approx(5.5).epsilon(1e-9));  // written to 9 digits
}

TEST_CASE("an unknown key is named with its line, column, nearest known key and the [notes] way out") {
  const std::string misspelt = error_of("name = \"x\"\nnmae = \"y\"\n[uncertainty]\nload_cell = 0.05\ndisplacement = 1e-6\n");
  CHECK(misspelt.find("metadata.toml:2:8: unknown key 'nmae'. Fix: did you mean 'name'? Known keys: name, notes, "
                      "uncertainty, test") != std::string::npos);
  CHECK(misspelt.find("[notes]") != std::string::npos);
  const std::string in_test =
      error_of("[uncertainty]\nload_cell = 0.05\ndisplacement = 1e-6\n[test]\nseating_preloda = 0.5\n");
  CHECK(in_test.find("metadata.toml:5:19: unknown key 'seating_preloda' in [test]. Fix: did you mean "
                     "'seating_preload'?") != std::string::npos);
  const std::string in_uncertainty = error_of("[uncertainty]\nload_cel = 0.05\ndisplacement = 1e-6\n");
  CHECK(in_uncertainty.find("unknown key 'load_cel' in [uncertainty]. Fix: did you mean 'load_cell'?") !=
        std::string::npos);
  CHECK(error_of("[uncertainty]\nload_cell = 0.05\ndisplacement = 1e-6\n[test]\nramp = \"cosine\"\n")
            .find("metadata.toml:5:8: [test] ramp is not a ramp") != std::string::npos);
  CHECK(error_of("[uncertainty]\nload_cell = 0.05\ndisplacement = 1e-6\n[test]\nramp = \"1-cos\"\n")
            .find("has no ramp_time") != std::string::npos);
  CHECK(error_of("[uncertainty]\nload_cell = 0.05\ndisplacement = 1e-6\n[test]\nseating_preload = -1\n")
            .find("[test] seating_preload must be a number >= 0") != std::string::npos);
}

TEST_CASE("a curve zeroed at the seating preload starts at (0, 0, preload), interpolated between samples") {
  Curve c;
  c.time = {0, 1, 2, 3, 4};
  c.displacement = {0, 1e-4, 2e-4, 3e-4, 4e-4};
  c.force = {0, 0.2, 0.6, 1.4, 3.0};
  c.u_displacement.assign(5, 1e-6);
  c.u_force.assign(5, 0.01);
  // 0.5 N is a quarter of the way from 0.2 N (sample 1) to 0.6 N (sample 2): t = 1.75, d = 1.75e-4.
  const Curve z = zeroed_at_preload(c, 0.5, "test curve");
  REQUIRE(z.size() == 4);
  CHECK(z.time[0] == 0.0);
  CHECK(z.displacement[0] == 0.0);
  CHECK(z.force[0] == 0.5);
  CHECK(z.time[1] == doctest::Approx(0.25).epsilon(1e-14));
  CHECK(z.displacement[1] == doctest::Approx(0.25e-4).epsilon(1e-12));
  CHECK(z.displacement[3] == doctest::Approx(2.25e-4).epsilon(1e-12));
  CHECK(z.force[3] == 3.0);
  CHECK(z.u_force.size() == 4);
  // A sample exactly at the preload is the zero itself (no duplicate point).
  const Curve on = zeroed_at_preload(c, 0.6, "test curve");
  REQUIRE(on.size() == 3);
  CHECK(on.displacement[0] == 0.0);
  CHECK(on.displacement[1] == doctest::Approx(1e-4).epsilon(1e-12));
  // A preload the curve never reaches is an error naming the curve and its largest force.
  try {
    zeroed_at_preload(c, 5.0, "the simulated curve of beam.toml");
    FAIL("no error");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("the simulated curve of beam.toml: the force never reaches the seating preload 5 N "
                                     "(its largest is 3 N)") != std::string::npos);
  }
}
