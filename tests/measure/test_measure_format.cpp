// The measurement folder format: a valid folder reads back exactly; each kind of bad file is
// refused with an error that names the file, line and column and says how to fix it.
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

const char* kMetadata = "name = \"test\"\n[uncertainty]\nload_cell = 0.5\ndisplacement = 1e-6\n";
const char* kSpecimens =
    "id,length,width,height,span,pin_distance,loading_rate,crack_position,fragment_count\n"
    "A,0.18,0.03,0.035,0.18,0.08,2e-4,0.004,3\n"
    "B,0.18,0.03,0.035,0.18,0.08,2e-4,,\n";
const char* kCurve =
    "# a comment\n"
    "time,displacement,force\n"
    "0,0,0\n1,1e-5,2\n2,2e-5,4\n3,3e-5,5.5\n4,4e-5,3\n5,5e-5,0.5\n";

fs::path make_folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("shard_measure_format_" + name);
  fs::remove_all(dir);
  write(dir / "metadata.toml", kMetadata);
  write(dir / "specimens.csv", kSpecimens);
  write(dir / "curves/A.csv", kCurve);
  write(dir / "curves/B.csv", kCurve);
  return dir;
}

// Runs the reader and returns the error it throws (fails the test when none is thrown).
MeasurementError error_of(const fs::path& dir) {
  try {
    read_measurements(dir);
  } catch (const MeasurementError& e) {
    return e;
  }
  FAIL("the reader accepted a bad folder");
  return MeasurementError("", 0, 0, "", "");
}

}  // namespace

TEST_CASE("a valid folder reads back with uncertainties from the metadata") {
  const auto dir = make_folder("valid");
  write(dir / "fragments/A.csv", "size\n0.01\n0.02\n0.03\n");
  const MeasurementSet set = read_measurements(dir);
  REQUIRE(set.specimens.size() == 2);
  const Specimen& a = set.specimens[0];
  CHECK(a.id == "A");
  CHECK(a.height == doctest::Approx(0.035).scale(0));
  CHECK(a.pin_distance == doctest::Approx(0.08).scale(0));
  REQUIRE(a.crack_position);
  CHECK(*a.crack_position == doctest::Approx(0.004).scale(0));
  CHECK(*a.fragment_count == doctest::Approx(3));
  CHECK(!set.specimens[1].crack_position);
  REQUIRE(a.curve.size() == 6);
  CHECK(a.curve.force[3] == doctest::Approx(5.5));
  CHECK(a.curve.u_force[3] == doctest::Approx(0.5));
  CHECK(a.curve.u_displacement[0] == doctest::Approx(1e-6).scale(0));
  CHECK(a.fragment_sizes.size() == 3);
  CHECK(set.specimens[1].fragment_sizes.empty());
  CHECK(set.loading_rates().size() == 1);
}

TEST_CASE("writer and reader round-trip") {
  const auto dir = make_folder("roundtrip_src");
  MeasurementSet set = read_measurements(dir);
  set.specimens[0].curve.u_force[2] = 0.75;  // per-point uncertainty survives via the u_force column
  const auto out = fs::temp_directory_path() / "shard_measure_format_roundtrip_out";
  fs::remove_all(out);
  write_measurements(set, out);
  const MeasurementSet back = read_measurements(out);
  REQUIRE(back.specimens.size() == 2);
  CHECK(back.specimens[0].curve.u_force[2] == doctest::Approx(0.75));
  CHECK(back.specimens[0].curve.force == set.specimens[0].curve.force);
  CHECK(*back.specimens[0].crack_position == doctest::Approx(0.004).scale(0));
  CHECK(back.metadata.load_cell_uncertainty == doctest::Approx(0.5));
}

TEST_CASE("missing column: names the column, the header line and the fix") {
  const auto dir = make_folder("missing_column");
  write(dir / "curves/B.csv", "time,displacement\n0,0\n1,1\n2,2\n3,3\n4,4\n");
  const auto e = error_of(dir);
  CHECK(e.file().filename() == "B.csv");
  CHECK(e.line() == 1);
  CHECK(std::string(e.what()).find("'force'") != std::string::npos);
  CHECK(e.fix().find("add a column named 'force'") != std::string::npos);
}

TEST_CASE("time going backwards: line and column of the offending value") {
  const auto dir = make_folder("time_order");
  write(dir / "curves/A.csv", "time,displacement,force\n0,0,0\n1,1e-5,1\n3,2e-5,2\n2,3e-5,3\n4,4e-5,1\n");
  const auto e = error_of(dir);
  CHECK(e.file().filename() == "A.csv");
  CHECK(e.line() == 5);
  CHECK(e.column() == 1);
  CHECK(e.problem().find("not increasing") != std::string::npos);
}

TEST_CASE("NaN force: line and column, and advice to drop the row") {
  const auto dir = make_folder("nan");
  write(dir / "curves/A.csv", "time,displacement,force\n0,0,0\n1,1e-5,1\n2,2e-5,NaN\n3,3e-5,3\n4,4e-5,1\n");
  const auto e = error_of(dir);
  CHECK(e.line() == 4);
  CHECK(e.column() == 3);
  CHECK(e.problem().find("NaN") != std::string::npos);
}

TEST_CASE("misspelt column, text in a number, wrong field count, bad geometry, duplicate id") {
  SUBCASE("misspelt") {
    const auto dir = make_folder("misspelt");
    write(dir / "curves/A.csv", "time,displacment,force\n0,0,0\n1,1,1\n2,2,2\n3,3,3\n4,4,4\n");
    const auto e = error_of(dir);
    CHECK(e.column() == 2);
    CHECK(e.fix().find("'displacement'") != std::string::npos);
  }
  SUBCASE("text") {
    const auto dir = make_folder("text");
    write(dir / "specimens.csv",
          "id,length,width,height,span,pin_distance,loading_rate\nA,0.18,0.03,35mm,0.18,0.08,2e-4\n");
    const auto e = error_of(dir);
    CHECK(e.file().filename() == "specimens.csv");
    CHECK(e.line() == 2);
    CHECK(e.column() == 4);
    CHECK(e.problem().find("'35mm'") != std::string::npos);
  }
  SUBCASE("field count") {
    const auto dir = make_folder("fields");
    write(dir / "curves/A.csv", "time,displacement,force\n0,0,0\n1,1\n");
    CHECK(error_of(dir).line() == 3);
  }
  SUBCASE("geometry") {
    const auto dir = make_folder("geometry");
    write(dir / "specimens.csv", "id,length,width,height,span,pin_distance,loading_rate\nA,0.18,0.03,0.035,0.08,0.1,2e-4\n");
    CHECK(error_of(dir).problem().find("not a four-point bending") != std::string::npos);
  }
  SUBCASE("duplicate id") {
    const auto dir = make_folder("duplicate");
    write(dir / "specimens.csv",
          "id,length,width,height,span,pin_distance,loading_rate\nA,0.18,0.03,0.035,0.18,0.08,2e-4\n"
          "A,0.18,0.03,0.035,0.18,0.08,2e-4\n");
    CHECK(error_of(dir).line() == 3);
  }
  SUBCASE("metadata without load-cell uncertainty") {
    const auto dir = make_folder("metadata");
    write(dir / "metadata.toml", "[uncertainty]\ndisplacement = 1e-6\n");
    const auto e = error_of(dir);
    CHECK(e.file().filename() == "metadata.toml");
    CHECK(e.fix().find("load_cell") != std::string::npos);
  }
}

TEST_CASE("lab exports: a ';' curve with decimal commas and a units row, a specimens file with BOM and CRLF") {
  const auto dir = make_folder("lab_export");
  // kCurve's values in mm, kN and ms, as a German testing machine writes them.
  write(dir / "curves/A.csv",
        "time;displacement;force\n"
        "ms;mm;kN\n"
        "0;0;0\n1000;0,01;0,002\n2000;0,02;0,004\n3000;0,03;0,0055\n4000;0,04;0,003\n5000;0,05;0,0005\n");
  write(dir / "specimens.csv",
        "\xEF\xBB\xBFid,length,width,height,span,pin_distance,loading_rate,crack_position,fragment_count\r\n"
        "A,0.18,0.03,0.035,0.18,0.08,2e-4,0.004,3\r\n"
        "B,0.18,0.03,0.035,0.18,0.08,2e-4,,\r\n");
  const MeasurementSet lab = read_measurements(dir);
  const MeasurementSet plain = read_measurements(make_folder("lab_export_plain"));
  REQUIRE(lab.specimens.size() == 2);
  CHECK(lab.specimens[0].id == "A");
  CHECK(lab.specimens[0].height == plain.specimens[0].height);
  const auto& a = lab.specimens[0].curve;
  const auto& p = plain.specimens[0].curve;
  REQUIRE(a.size() == p.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    // One conversion (e.g. 0,0055 kN * 1e3) differs from the plain text by at most an ulp or two.
    CHECK(a.time[k] == doctest::Approx(p.time[k]).epsilon(1e-15));
    CHECK(a.displacement[k] == doctest::Approx(p.displacement[k]).epsilon(1e-15));
    CHECK(a.force[k] == doctest::Approx(p.force[k]).epsilon(1e-15));
  }
}

TEST_CASE("units in the column names: a curve as shard run writes it and one in ms, mm and kN") {
  const auto dir = make_folder("unit_names");
  write(dir / "curves/A.csv",
        "time_s,displacement_m,force_N\n0,0,0\n1,1e-5,2\n2,2e-5,4\n3,3e-5,5.5\n4,4e-5,3\n5,5e-5,0.5\n");
  write(dir / "curves/B.csv",
        "time [ms],displacement_mm,force_kN\n0,0,0\n1000,0.01,0.002\n2000,0.02,0.004\n3000,0.03,0.0055\n"
        "4000,0.04,0.003\n5000,0.05,0.0005\n");
  const MeasurementSet named = read_measurements(dir);
  const MeasurementSet plain = read_measurements(make_folder("unit_names_plain"));
  for (std::size_t s = 0; s < 2; ++s) {
    const auto& a = named.specimens[s].curve;
    const auto& p = plain.specimens[s].curve;
    REQUIRE(a.size() == p.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      CHECK(a.time[k] == doctest::Approx(p.time[k]).epsilon(1e-15));
      CHECK(a.displacement[k] == doctest::Approx(p.displacement[k]).epsilon(1e-15));
      CHECK(a.force[k] == doctest::Approx(p.force[k]).epsilon(1e-15));
    }
  }
  // A suffix that is no unit stays part of the name, and the error says so.
  write(dir / "curves/A.csv", "time_x,displacement,force\n0,0,0\n1,1e-5,2\n2,2e-5,4\n");
  CHECK(std::string(error_of(dir).what()).find("unknown column 'time_x'") != std::string::npos);
}

TEST_CASE("a ragged lab export names file, line and field") {
  const auto dir = make_folder("lab_ragged");
  write(dir / "curves/B.csv", "time;displacement;force\ns;m;N\n0;0;0\n1;1e-5\n");
  const auto e = error_of(dir);
  CHECK(e.file().filename() == "B.csv");
  CHECK(e.line() == 4);
  CHECK(e.column() == 3);
  CHECK(e.problem() == "the line has 2 fields but the header has 3 (time,displacement,force)");
}
