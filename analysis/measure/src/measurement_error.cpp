#include "shard/measure/measurement_error.hpp"

#include <fmt/format.h>

namespace shard::measure {
namespace {

std::string where(const std::filesystem::path& file, long line, long column) {
  if (line <= 0) return file.string();
  if (column <= 0) return fmt::format("{}:{}", file.string(), line);
  return fmt::format("{}:{}:{}", file.string(), line, column);
}

}  // namespace

MeasurementError::MeasurementError(std::filesystem::path file, long line, long column, const std::string& problem,
                                   const std::string& fix)
    : std::runtime_error(fmt::format("{}: {}. Fix: {}", where(file, line, column), problem, fix)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      problem_(problem),
      fix_(fix) {}

}  // namespace shard::measure
