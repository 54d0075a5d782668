#include "shard/measure/csv_table.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

#include "shard/measure/measurement_error.hpp"

namespace shard::measure {
namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// Levenshtein distance, for "did you mean" hints on misspelt column names.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0u : 1u)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

CsvTable CsvTable::read(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in)
    throw MeasurementError(file, 0, 0, "the file cannot be opened",
                           "check the path; see docs/measurements.md for the folder layout");
  CsvTable t;
  t.file_ = file;
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string content = trim(line);
    if (content.empty() || content[0] == '#') continue;
    auto fields = split(content);
    if (t.header_.empty()) {
      t.header_ = std::move(fields);
      t.header_line_ = number;
      for (std::size_t c = 0; c < t.header_.size(); ++c) {
        if (t.header_[c].empty())
          throw MeasurementError(file, number, static_cast<long>(c + 1), "the header has an empty column name",
                                 "name every column or remove the trailing comma");
        for (std::size_t d = 0; d < c; ++d)
          if (t.header_[d] == t.header_[c])
            throw MeasurementError(file, number, static_cast<long>(c + 1),
                                   fmt::format("column '{}' appears twice in the header", t.header_[c]),
                                   "keep one column of each name");
      }
      continue;
    }
    if (fields.size() != t.header_.size())
      throw MeasurementError(file, number, static_cast<long>(std::min(fields.size(), t.header_.size()) + 1),
                             fmt::format("the line has {} fields but the header has {} ({})", fields.size(),
                                         t.header_.size(), fmt::join(t.header_, ",")),
                             "write one value per header column (an empty optional value is just ',,')");
    t.rows_.push_back({number, std::move(fields)});
  }
  if (t.header_.empty())
    throw MeasurementError(file, 0, 0, "the file is empty (no header line)",
                           "start the file with a header line naming the columns");
  return t;
}

std::optional<std::size_t> CsvTable::find(const std::string& name) const {
  const auto it = std::find(header_.begin(), header_.end(), name);
  if (it == header_.end()) return std::nullopt;
  return static_cast<std::size_t>(it - header_.begin());
}

std::size_t CsvTable::require(const std::string& name, const std::string& meaning) const {
  if (auto c = find(name)) return *c;
  throw MeasurementError(file_, header_line_, 0,
                         fmt::format("required column '{}' ({}) is missing; the header is: {}", name, meaning,
                                     fmt::join(header_, ",")),
                         fmt::format("add a column named '{}' to the header line", name));
}

void CsvTable::reject_unknown(const std::vector<std::string>& known) const {
  for (std::size_t c = 0; c < header_.size(); ++c) {
    if (std::find(known.begin(), known.end(), header_[c]) != known.end()) continue;
    const std::string closest = closest_name(header_[c], known);
    throw MeasurementError(file_, header_line_, static_cast<long>(c + 1),
                           fmt::format("unknown column '{}'", header_[c]),
                           !closest.empty() ? fmt::format("did you mean '{}'?", closest)
                                            : fmt::format("the known columns are: {}", fmt::join(known, ", ")));
  }
}

std::string closest_name(const std::string& word, const std::vector<std::string>& known) {
  std::string closest;
  std::size_t best = 4;
  for (const auto& k : known)
    if (const auto d = edit_distance(word, k); d < best) best = d, closest = k;
  return closest;
}

const std::string& CsvTable::text(const CsvRow& row, std::size_t column) const { return row.fields.at(column); }

std::optional<double> CsvTable::optional_number(const CsvRow& row, std::size_t column,
                                                const std::string& unit_hint) const {
  if (row.fields.at(column).empty()) return std::nullopt;
  return number(row, column, unit_hint);
}

double CsvTable::number(const CsvRow& row, std::size_t column, const std::string& unit_hint) const {
  const std::string& s = row.fields.at(column);
  const long col = static_cast<long>(column + 1);
  if (s.empty())
    throw MeasurementError(file_, row.line, col, fmt::format("column '{}' is empty", header_[column]),
                           fmt::format("write the {}", unit_hint));
  double value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  const bool nan_text = s.find("nan") != std::string::npos || s.find("NaN") != std::string::npos ||
                        s.find("NAN") != std::string::npos;
  if (nan_text || (ec == std::errc() && std::isnan(value)))
    throw MeasurementError(file_, row.line, col, fmt::format("column '{}' is NaN", header_[column]),
                           "remove the row or replace the NaN by the measured value (a gap in the recording "
                           "is better left out than filled)");
  if (ec != std::errc() || end != s.data() + s.size())
    throw MeasurementError(file_, row.line, col, fmt::format("column '{}' is '{}', not a number", header_[column], s),
                           fmt::format("write the {} as a plain number (decimal point, no unit)", unit_hint));
  if (!std::isfinite(value))
    throw MeasurementError(file_, row.line, col, fmt::format("column '{}' is infinite", header_[column]),
                           "write a finite value or remove the row");
  return value;
}

}  // namespace shard::measure
