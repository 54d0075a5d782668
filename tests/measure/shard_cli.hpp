#pragma once
// The measurement loop's end-to-end tests run the shard binary as a user does and read what it
// wrote (diagnose.json, calibrate.json): these are the few helpers they share.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace shard_test {

// `shard ARGS`, its output appended to WORK/log.txt; the test stops when it fails.
inline void run_shard(const std::string& args, const std::filesystem::path& work) {
  std::filesystem::create_directories(work);
  const std::string cmd =
      std::string(SHARD_BUILD_DIR) + "/bin/shard " + args + " >> " + (work / "log.txt").string() + " 2>&1";
  INFO(cmd);
  REQUIRE(std::system(cmd.c_str()) == 0);
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A JSON document a command wrote, read with nlohmann's strict parser (a `nan` or a stray comma
// fails the test), whose format_version must be the one the test was written for.
inline nlohmann::json read_document(const std::filesystem::path& p, int format_version) {
  const std::string text = read_text(p);
  INFO(p.string() << ":\n" << text);
  nlohmann::json document;
  REQUIRE_NOTHROW(document = nlohmann::json::parse(text));
  REQUIRE(document.contains("format_version"));
  CHECK(document["format_version"] == format_version);
  return document;
}

// The first element of an array of objects whose `key` is `value`; the test stops when none is.
inline const nlohmann::json& element_with(const nlohmann::json& array, const std::string& key, const std::string& value) {
  for (const auto& e : array)
    if (e.value(key, std::string()) == value) return e;
  INFO("no element with " << key << " = " << value << " in " << array.dump());
  REQUIRE(false);
  return array;
}

inline std::size_t find_key(const std::string& text, const std::string& key, std::size_t from = 0) {
  const auto at = text.find(key, from);
  INFO("missing " << key);
  REQUIRE(at != std::string::npos);
  return at;
}

inline double number_after(const std::string& text, const std::string& key, std::size_t from = 0) {
  return std::stod(text.substr(find_key(text, key, from) + key.size()));
}

inline std::string string_after(const std::string& text, const std::string& key, std::size_t from = 0) {
  const auto start = find_key(text, key, from) + key.size();
  return text.substr(start, text.find('"', start) - start);
}

}  // namespace shard_test
