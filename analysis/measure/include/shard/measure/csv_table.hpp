#pragma once
// A comma-separated table with a header line, kept as text so every value can be reported with
// its file, line and column when it does not parse. '#' starts a comment line; blank lines are
// skipped; fields are trimmed.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace shard::measure {

struct CsvRow {
  long line = 0;  // 1-based line in the file
  std::vector<std::string> fields;
};

class CsvTable {
 public:
  static CsvTable read(const std::filesystem::path& file);

  const std::filesystem::path& file() const { return file_; }
  const std::vector<std::string>& header() const { return header_; }
  const std::vector<CsvRow>& rows() const { return rows_; }

  // 0-based column index; nullopt when absent.
  std::optional<std::size_t> find(const std::string& name) const;
  // As find, but a missing column is an error that lists the header and says how to fix it.
  std::size_t require(const std::string& name, const std::string& meaning) const;
  // Rejects columns not in `known`, naming the closest known one.
  void reject_unknown(const std::vector<std::string>& known) const;

  // The value in `column` of `row` as a finite number; empty cells are errors.
  double number(const CsvRow& row, std::size_t column, const std::string& unit_hint) const;
  // nullopt for an empty cell, otherwise as number().
  std::optional<double> optional_number(const CsvRow& row, std::size_t column, const std::string& unit_hint) const;
  const std::string& text(const CsvRow& row, std::size_t column) const;

 private:
  std::filesystem::path file_;
  std::vector<std::string> header_;
  long header_line_ = 0;
  std::vector<CsvRow> rows_;
};

// The name in `known` nearest to `word` within 3 edits (Levenshtein), or "" when none is: the
// "did you mean" hint of every unknown column and key.
std::string closest_name(const std::string& word, const std::vector<std::string>& known);

}  // namespace shard::measure
