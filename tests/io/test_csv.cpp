// The one CSV reader on what Shard writes and what testing machines export: separators, decimal
// commas, quotes, units rows, a byte-order mark, CRLF; and broken files, which must be refused with
// file:line:column and a fix.
#include <doctest/doctest.h>

#include <string>

#include "shard/io/csv.hpp"
#include "shard/io/units.hpp"

using shard::io::CsvError;
using shard::io::CsvHeader;
using shard::io::CsvTable;

namespace {

std::string error_of(const std::string& text, CsvHeader header = CsvHeader::required) {
  try {
    const auto t = CsvTable::parse(text, "lab.csv", header);
    for (const auto& row : t.rows())
      for (std::size_t c = 0; c < row.fields.size(); ++c) t.number(row, c, "value");
  } catch (const CsvError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("a Zwick-like export: ';', German decimal commas, a units row in kN and mm") {
  const std::string text =
      "Prüfzeit;Standardweg;Standardkraft\n"
      "s;mm;kN\n"
      "0,000;0,000;0,0012\n"
      "0,100;0,0125;0,0503\n"
      "0,200;0,0250;1,25\n";
  const auto t = CsvTable::parse(text, "zwick.csv");
  CHECK(t.separator() == ';');
  CHECK(t.decimal_comma());
  REQUIRE(t.header().size() == 3);
  CHECK(t.header()[0] == "Prüfzeit");
  CHECK(t.units() == std::vector<std::string>{"s", "mm", "kN"});
  REQUIRE(t.rows().size() == 3);
  CHECK(t.rows()[0].line == 3);
  const auto& last = t.rows()[2];
  CHECK(t.number(last, 0, "time") == doctest::Approx(0.2).epsilon(1e-15));
  CHECK(t.number(last, 1, "displacement") == doctest::Approx(25e-6).epsilon(1e-15));  // mm -> m
  CHECK(t.number(last, 2, "force") == doctest::Approx(1250).epsilon(1e-15));          // kN -> N
}

TEST_CASE("an Instron-like export: UTF-8 byte-order mark, CRLF, quoted names, bracketed units") {
  const std::string text =
      "\xEF\xBB\xBF\"Time\",\"Extension, crosshead\",\"Load\"\r\n"
      "\"(s)\",\"(mm)\",\"(N)\"\r\n"
      "0.0,0.000,0.12\r\n"
      "0.5,0.010,\"15.5\"\r\n";
  const auto t = CsvTable::parse(text, "instron.csv");
  CHECK(t.separator() == ',');
  CHECK_FALSE(t.decimal_comma());
  CHECK(t.header() == std::vector<std::string>{"Time", "Extension, crosshead", "Load"});
  CHECK(t.units() == std::vector<std::string>{"(s)", "(mm)", "(N)"});
  REQUIRE(t.rows().size() == 2);
  CHECK(t.number(t.rows()[1], 1, "extension") == doctest::Approx(1e-5).epsilon(1e-15));
  CHECK(t.number(t.rows()[1], 2, "load") == 15.5);
  CHECK(t.rows()[1].line == 4);
}

TEST_CASE("Shard's own tables: ',' with no units row, comments kept, tabs sniffed, optional header") {
  const auto plain = CsvTable::parse("#! span_mm = 180\ntime,force\n# note\n0,1\n1,2\n", "curve.csv");
  CHECK(plain.units().empty());
  CHECK(plain.rows().size() == 2);
  REQUIRE(plain.comments().size() == 2);
  CHECK(plain.comments()[0].text == "! span_mm = 180");
  const auto tabs = CsvTable::parse("d\tF\n[mm]\t[N]\n1,5\t2\n", "tabs.tsv");
  CHECK(tabs.separator() == '\t');
  CHECK(tabs.number(tabs.rows()[0], 0, "d") == doctest::Approx(1.5e-3).epsilon(1e-15));
  const auto headless = CsvTable::parse("0.1,0.2,0.3,0.01\n", "spheres.csv", CsvHeader::optional);
  CHECK(headless.header().empty());
  CHECK(headless.rows().size() == 1);
  const auto headed = CsvTable::parse("x,y,z,r\n0.1,0.2,0.3,0.01\n", "spheres.csv", CsvHeader::optional);
  CHECK(headed.header().size() == 4);
}

TEST_CASE("broken files are refused with file:line:column and a fix") {
  CHECK(error_of("a;b;c\n1;2;3\n4;5\n") ==
        "lab.csv:3:4: the line has 2 fields but the header has 3 (a,b,c); write one value per column, separated by "
        "';' (an empty value is just two separators)");
  CHECK(error_of("a,b\n1,2,3\n").find("lab.csv:2:5: the line has 3 fields but the header has 2") == 0);
  CHECK(error_of("time;force\n0;1\n0,5;fast\n") ==
        "lab.csv:3:5: column 'force' is 'fast', not a number; write the value as a plain number (decimal point or "
        "comma, no unit, no thousands separator)");
  CHECK(error_of("time;force\n0;1.234,5\n").find("lab.csv:2:3: column 'force' is '1.234,5', not a number") == 0);
  CHECK(error_of("time,force\n0,nan\n").find("lab.csv:2:3: column 'force' is NaN") == 0);
  CHECK(error_of("time,force\n0,\n").find("lab.csv:2:3: column 'force' is empty") == 0);
  CHECK(error_of("") == "lab.csv:0:0: the file is empty (no header line and no rows); start the file with a header "
                        "line naming the columns, then one row per line");
  CHECK(error_of("\xEF\xBB\xBF\r\n# only a comment\r\n").find("the file is empty") != std::string::npos);
  CHECK(error_of("a,\"b\nc,d\n").find("lab.csv:1:3: the quote that opens this field is not closed") == 0);
  CHECK(error_of("a,\"b\"x\n").find("lab.csv:1:6: text follows the closing quote") == 0);
  CHECK(error_of("a,a\n").find("lab.csv:1:3: column 'a' appears twice") == 0);
  CHECK(error_of("0.1,0.2\n0.3\n", CsvHeader::optional).find("lab.csv:2:4: the line has 1 fields but the first row "
                                                             "has 2") == 0);
  try {
    CsvTable::read("no/such/file.csv");
    FAIL("no error");
  } catch (const CsvError& e) {
    CHECK(std::string(e.what()) == "no/such/file.csv:0:0: the file cannot be opened; check the path");
  }
}

TEST_CASE("numbers and units") {
  CHECK(shard::io::parse_csv_number("1,5", true) == 1.5);
  CHECK_FALSE(shard::io::parse_csv_number("1,5", false));
  CHECK(shard::io::parse_csv_number("+2e3", false) == 2000.0);
  CHECK_FALSE(shard::io::parse_csv_number("inf", false));
  CHECK_FALSE(shard::io::parse_csv_number("1,000,5", true));
  CHECK(shard::io::si_factor_of_unit("[mm/min]") == doctest::Approx(1e-3 / 60).epsilon(1e-15));
  CHECK(shard::io::si_factor_of_unit(" N/mm² ") == 1e6);
  CHECK_FALSE(shard::io::si_factor_of_unit("lbf"));
}

TEST_CASE("a unit in a column name") {
  using shard::io::split_unit_from_name;
  CHECK(split_unit_from_name("force_kN").name == "force");
  CHECK(split_unit_from_name("force_kN").factor == 1e3);
  CHECK(split_unit_from_name("Standardkraft [N]").name == "Standardkraft");
  CHECK(split_unit_from_name("w (mm)").factor == 1e-3);
  CHECK(split_unit_from_name("u_displacement_mm").name == "u_displacement");
  // What follows the '_' is no unit: the name stays whole.
  CHECK(split_unit_from_name("u_force").name == "u_force");
  CHECK_FALSE(split_unit_from_name("loading_rate").has_unit);
  CHECK_FALSE(split_unit_from_name("_s").has_unit);
}
