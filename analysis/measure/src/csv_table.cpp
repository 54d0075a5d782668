#include "shard/measure/csv_table.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "shard/measure/measurement_error.hpp"

namespace shard::measure {
namespace {

MeasurementError located(const io::CsvError& e) {
  return MeasurementError(e.file(), e.line(), e.field(), e.problem(), e.fix());
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
  if (!std::filesystem::is_regular_file(file))
    throw MeasurementError(file, 0, 0, "the file cannot be opened",
                           "check the path; see docs/how-to/bring-lab-data.md for the folder layout");
  try {
    return CsvTable(file, io::CsvTable::read(file));
  } catch (const io::CsvError& e) {
    throw located(e);
  }
}

CsvTable::CsvTable(std::filesystem::path file, io::CsvTable table) : file_(std::move(file)), table_(std::move(table)) {
  for (const std::string& column : table_.header())
    names_.push_back(table_.units().empty() ? io::split_unit_from_name(column) : io::NameWithUnit{column, 1, false});
}

std::optional<std::size_t> CsvTable::find(const std::string& name) const {
  for (std::size_t c = 0; c < names_.size(); ++c)
    if (names_[c].name == name) return c;
  return std::nullopt;
}

std::size_t CsvTable::require(const std::string& name, const std::string& meaning) const {
  if (auto c = find(name)) return *c;
  throw MeasurementError(file_, table_.header_line(), 0,
                         fmt::format("required column '{}' ({}) is missing; the header is: {}", name, meaning,
                                     fmt::join(header(), ",")),
                         fmt::format("add a column named '{}' to the header line", name));
}

void CsvTable::reject_unknown(const std::vector<std::string>& known) const {
  for (std::size_t c = 0; c < header().size(); ++c) {
    if (std::find(known.begin(), known.end(), names_[c].name) != known.end()) continue;
    const std::string closest = closest_name(names_[c].name, known);
    throw MeasurementError(file_, table_.header_line(), static_cast<long>(c + 1),
                           fmt::format("unknown column '{}'", header()[c]),
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
  try {
    return names_.at(column).factor * table_.number(row, column, unit_hint);
  } catch (const io::CsvError& e) {
    throw located(e);
  }
}

}  // namespace shard::measure
