// The JSON helper: what a document holds, how non-finite numbers and odd text are written, that a
// write is atomic, and that every read error names the file and the line/column or key.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "shard/io/json.hpp"

namespace fs = std::filesystem;
using shard::io::Json;
using shard::io::JsonError;
using shard::io::JsonFields;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "test_io_json";
  fs::create_directories(dir);
  return dir / name;
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

std::string message_of(auto&& read) {
  try {
    read();
  } catch (const JsonError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("a document starts with its format version and the Shard version") {
  Json d = shard::io::json_document(3);
  d["x"] = 1.5;
  CHECK(d.begin().key() == "format_version");
  CHECK(d["format_version"] == 3);
  CHECK(d["shard_version"] == std::string(shard::io::shard_version()));
  CHECK(std::string(shard::io::shard_version()).find('.') != std::string::npos);
  CHECK(shard::io::json_text(d).back() == '\n');
}

TEST_CASE("non-finite numbers are written as null and text is escaped so a strict parser reads it back") {
  Json d = shard::io::json_document(1);
  d["nan"] = std::numeric_limits<double>::quiet_NaN();
  d["inf"] = -std::numeric_limits<double>::infinity();
  d["text"] = "tab\there \"quoted\" back\\slash\x01 und Übermaß";
  d["small"] = 1.2345678901234567e-300;
  const std::string text = shard::io::json_text(d);
  CHECK(text.find(": nan") == std::string::npos);
  CHECK(text.find(": -inf") == std::string::npos);
  CHECK(text.find("\"nan\": null") != std::string::npos);
  const Json back = Json::parse(text);  // throws on anything that is not JSON
  CHECK(back["nan"].is_null());
  CHECK(back["inf"].is_null());
  CHECK(back["text"] == d["text"]);
  CHECK(back["small"].get<double>() == d["small"].get<double>());  // shortest round-trip digits
  const JsonFields f(back, "memory");
  CHECK(std::isnan(f.number("nan")));
}

TEST_CASE("a JSON Lines record is one line however its strings break, and parses back with its line number") {
  Json d = shard::io::json_document(1);
  d["label"] = "two\nlines";
  d["nan"] = std::numeric_limits<double>::quiet_NaN();
  const std::string line = shard::io::json_line(d);
  CHECK(line.back() == '\n');
  CHECK(std::count(line.begin(), line.end(), '\n') == 1);
  const Json back = shard::io::parse_json(line.substr(0, line.size() - 1), "history.jsonl", 4);
  CHECK(back["label"] == "two\nlines");
  CHECK(back["nan"].is_null());
  try {
    (void)shard::io::parse_json("{\"a\": nan}", "history.jsonl", 4);
    FAIL("nan is not JSON");
  } catch (const shard::io::JsonError& e) {
    CHECK(std::string(e.what()).find("history.jsonl:4:") == 0);
  }
}

TEST_CASE("write_json replaces the file whole and leaves no temporary file") {
  const fs::path file = scratch("atomic.json");
  write_text(file, "old");
  Json d = shard::io::json_document(2);
  d["k"] = 7;
  shard::io::write_json(file, d);
  const Json back = shard::io::read_json_document(file, "test document", 2);
  CHECK(JsonFields(back, file.string()).integer("k") == 7);
  for (const auto& entry : fs::directory_iterator(file.parent_path()))
    CHECK(entry.path().filename().string().find(".tmp.") == std::string::npos);
  const std::string error = message_of([] { shard::io::write_json(scratch("no_such_dir") / "x.json", Json::object()); });
  CHECK(error.find("no_such_dir/x.json: cannot be written") != std::string::npos);
}

TEST_CASE("a syntax error names the file, line and column") {
  const fs::path file = scratch("broken.json");
  write_text(file, "{\n  \"a\": 1,\n  \"b\": nan\n}\n");  // the parser stops at the a of nan
  const std::string error = message_of([&] { shard::io::read_json(file); });
  CHECK(error.find(file.string() + ":3:9: not valid JSON") != std::string::npos);
  // A line of a JSON Lines file keeps its own line number.
  const std::string line_error = message_of([] { shard::io::parse_json("{\"a\": }", "history.jsonl", 12); });
  CHECK(line_error.find("history.jsonl:12:7:") != std::string::npos);
  const std::string missing = message_of([] { shard::io::read_json(scratch("absent.json")); });
  CHECK(missing.find("absent.json: cannot be opened") != std::string::npos);
}

TEST_CASE("a missing or mistyped key is named with its path") {
  const Json d = Json::parse(R"({"format_version": 1, "runs": [{"force": 1}, {"force": "high"}], "n": 1.5})");
  const JsonFields f(d, "report.json");
  CHECK(message_of([&] { f.number("absent"); }) ==
        "report.json: key 'absent' (a number) is missing; add it to the document");
  CHECK(message_of([&] { f.objects("runs")[1].number("force"); }) ==
        "report.json: key 'runs[1].force' is text, expected a number");
  CHECK(message_of([&] { f.integer("n"); }) == "report.json: key 'n' is a number, expected an integer");
  CHECK(f.objects("runs")[0].number("force") == 1.0);
  CHECK_FALSE(f.optional_number("absent").has_value());
}

TEST_CASE("format versions: newer files are refused, a file without one is not a document") {
  const fs::path newer = scratch("newer.json");
  write_text(newer, R"({"format_version": 5, "shard_version": "9.0.0"})");
  const std::string error = message_of([&] { shard::io::read_json_document(newer, "bending report", 1); });
  CHECK(error.find("'format_version' is 5") != std::string::npos);
  CHECK(error.find("reads bending report files of format version 1 to 1") != std::string::npos);
  const fs::path none = scratch("none.json");
  write_text(none, R"({"a": 1})");
  CHECK(message_of([&] { shard::io::read_json_document(none, "bending report", 1); })
            .find("key 'format_version' (an integer) is missing") != std::string::npos);
  const fs::path list = scratch("list.json");
  write_text(list, "[1, 2]");
  CHECK(message_of([&] { shard::io::read_json_document(list, "bending report", 1); })
            .find("is a JSON object {...}, this file holds an array") != std::string::npos);
}
