#pragma once
// The measurement loop's end-to-end tests run the shard binary as a user does and read what it
// wrote (diagnose.json, calibrate.json): these are the few helpers they share.
#include <doctest/doctest.h>

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
