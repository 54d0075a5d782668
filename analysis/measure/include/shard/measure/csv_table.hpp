#pragma once
// A measurement table with a header line, read by the one CSV reader (shard/io/csv.hpp: ',' or
// ';' or tab, decimal commas, quotes, a units row applied to SI, a byte-order mark, CRLF) and kept
// as text so every value can be reported with its file, line and column when it does not parse.
// '#' starts a comment line; blank lines are skipped; fields are trimmed. Problems are
// MeasurementError, whose column is the 1-based field of the table.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shard/io/csv.hpp"
#include "shard/io/units.hpp"

namespace shard::measure {

using CsvRow = io::CsvRow;  // line (1-based) and the fields

class CsvTable {
 public:
  static CsvTable read(const std::filesystem::path& file);

  const std::filesystem::path& file() const { return file_; }
  const std::vector<std::string>& header() const { return table_.header(); }
  const std::vector<CsvRow>& rows() const { return table_.rows(); }

  // 0-based column index; nullopt when absent. Without a units row, a column may carry its unit
  // in its name (time_s, force_kN: io::split_unit_from_name), as `shard run` writes its curves;
  // it is then found by the quantity's name and read in SI.
  std::optional<std::size_t> find(const std::string& name) const;
  // As find, but a missing column is an error that lists the header and says how to fix it.
  std::size_t require(const std::string& name, const std::string& meaning) const;
  // Rejects columns not in `known`, naming the closest known one.
  void reject_unknown(const std::vector<std::string>& known) const;

  // The value in `column` of `row` as a finite number in SI (a units row or the unit in the
  // column's name is applied); empty cells are errors.
  double number(const CsvRow& row, std::size_t column, const std::string& unit_hint) const;
  // nullopt for an empty cell, otherwise as number().
  std::optional<double> optional_number(const CsvRow& row, std::size_t column, const std::string& unit_hint) const;
  const std::string& text(const CsvRow& row, std::size_t column) const;

 private:
  CsvTable(std::filesystem::path file, io::CsvTable table);
  std::filesystem::path file_;
  io::CsvTable table_;
  std::vector<io::NameWithUnit> names_;  // per column: the quantity and its unit from the name
};

// The name in `known` nearest to `word` within 3 edits (Levenshtein), or "" when none is: the
// "did you mean" hint of every unknown column and key.
std::string closest_name(const std::string& word, const std::vector<std::string>& known);

}  // namespace shard::measure
