// Load curves from testing machines through read_curve_csv: a Zwick-like export (';', German
// decimal commas, a units row in mm and kN), an Instron-like one (byte-order mark, CRLF, quoted
// names, bracketed units) and broken files, refused with file:line:column.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "shard/bending/curve_analysis.hpp"

namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string error_of(const std::string& name, const std::string& text) {
  const auto path = write_file(name, text);
  try {
    shard::bending::read_curve_csv(path);
  } catch (const std::runtime_error& e) {
    return std::string(e.what()).substr(path.size() - name.size());  // from the file name on
  }
  return "no error";
}

}  // namespace

TEST_CASE("a Zwick-like export: units row applied, decimal commas read") {
  const auto path = write_file("zwick.csv",
                               "Prüfzeit;Standardweg;Standardkraft\n"
                               "s;mm;kN\n"
                               "0;0;0\n"
                               "0,5;0,25;0,1125\n"
                               "1,0;0,50;0,2250\n");
  const auto curve = shard::bending::read_curve_csv(path);
  REQUIRE(curve.force.size() == 3);
  CHECK(curve.time[2] == 1.0);
  CHECK(curve.displacement[1] == doctest::Approx(0.25e-3).epsilon(1e-15));
  CHECK(curve.force[2] == doctest::Approx(225.0).epsilon(1e-15));
}

TEST_CASE("an Instron-like export: byte-order mark, CRLF, quoted names, bracketed units") {
  const auto path = write_file("instron.csv",
                               "\xEF\xBB\xBF\"Time\",\"Extension\",\"Load\"\r\n"
                               "\"(s)\",\"(mm)\",\"(N)\"\r\n"
                               "0.00,0.000,0.0\r\n"
                               "0.25,0.125,12.5\r\n");
  const auto curve = shard::bending::read_curve_csv(path);
  REQUIRE(curve.force.size() == 2);
  CHECK(curve.displacement[1] == doctest::Approx(0.125e-3).epsilon(1e-15));
  CHECK(curve.force[1] == 12.5);
}

TEST_CASE("Shard's own curve files keep their unit suffixes") {
  const auto curve = shard::bending::read_curve_csv(write_file("own.csv", "displacement_mm,force_kN\n0,0\n2,0.5\n"));
  CHECK(curve.displacement[1] == doctest::Approx(2e-3).epsilon(1e-15));
  CHECK(curve.force[1] == doctest::Approx(500).epsilon(1e-15));
}

TEST_CASE("broken curve files name file:line:column") {
  CHECK(error_of("ragged.csv", "Zeit;Weg;Kraft\ns;mm;N\n0;0;0\n1;0,1\n")
            .starts_with("ragged.csv:4:6: the line has 2 fields but the header has 3 (Zeit,Weg,Kraft)"));
  CHECK(error_of("word.csv", "displacement,force\n0,0\n0.1,high\n")
            .starts_with("word.csv:3:5: column 'force' is 'high', not a number"));
  CHECK(error_of("empty.csv", "").starts_with("empty.csv:0:0: the file is empty"));
  CHECK(error_of("columns.csv", "a,b\n1,2\n").starts_with("columns.csv:1: the header needs a displacement column"));
}
