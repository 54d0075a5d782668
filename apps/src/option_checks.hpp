#pragma once
// Range checks for numeric command-line options. CLI11 converts `--threads 0` or `--threads -3`
// without complaint; these refuse such values while parsing, before any work, with a message
// that says what the number means and what to give instead.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdlib>
#include <string>

namespace shard {

// Accepts numbers >= min (> min when `strict`); `meaning` completes "must be ...", e.g. "at
// least 1 (leave --threads out to use every core)". Text that is no number is left to CLI11's
// own conversion error.
inline CLI::Validator number_from(double min, bool strict, const std::string& meaning) {
  return CLI::Validator(
      [min, strict, meaning](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return {};
        if (strict ? value > min : value >= min) return {};
        return fmt::format("{} is out of range: the value must be {}", text, meaning);
      },
      fmt::format("{} {}", strict ? ">" : ">=", min));
}

// A count of OpenMP threads: at least one.
inline CLI::Validator thread_count() {
  return number_from(1, false, "at least 1 (leave --threads out to use every core)");
}

}  // namespace shard
