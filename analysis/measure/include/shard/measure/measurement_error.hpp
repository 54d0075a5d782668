#pragma once
// A problem in a user's measurement file, located so the user can go straight to it:
// "specimens.csv:4:3: column 'height' is 'abc', not a number. Fix: write the height in metres".
#include <filesystem>
#include <stdexcept>
#include <string>

namespace shard::measure {

class MeasurementError : public std::runtime_error {
 public:
  MeasurementError(std::filesystem::path file, long line, long column, const std::string& problem,
                   const std::string& fix);

  const std::filesystem::path& file() const { return file_; }
  long line() const { return line_; }      // 1-based; 0 = the whole file
  long column() const { return column_; }  // 1-based CSV column (field index); 0 = the whole line
  const std::string& problem() const { return problem_; }
  const std::string& fix() const { return fix_; }

 private:
  std::filesystem::path file_;
  long line_, column_;
  std::string problem_, fix_;
};

}  // namespace shard::measure
