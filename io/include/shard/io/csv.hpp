#pragma once
// The one reader of every CSV table Shard takes in (measurement folders, load curves, wall motion
// tables, size distributions, packings), reading what Shard writes and what a lab machine exports:
//  * the separator is sniffed from the first line (outside quotes): ';' if it has one, else a tab,
//    else ','; with ';' or a tab, numbers may use a decimal comma ("1,25");
//  * fields may be quoted ("a;b", "say ""x"""); spaces around a field are trimmed;
//  * a UTF-8 byte-order mark and CRLF line ends are accepted; blank lines and lines starting
//    with '#' are skipped (comments() keeps them, for "#! key = value" metadata);
//  * the header may be followed by a units row ("s;mm;kN" or "[s];[mm];[kN]"): it is recognised
//    when every non-empty field is a unit of units.hpp, and number() then returns SI values;
//  * every error names file:line:column (1-based; the column is the character where the field
//    starts) and says how to fix the file.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace shard::io {

// A located problem in a table. what() is "file:line:column: problem; fix".
class CsvError : public std::runtime_error {
 public:
  CsvError(std::string file, long line, long column, long field, std::string problem, std::string fix);
  const std::string& file() const { return file_; }
  long line() const { return line_; }      // 1-based; 0: the whole file
  long column() const { return column_; }  // 1-based character column; 0: the whole line
  long field() const { return field_; }    // 1-based field (column of the table); 0: none
  const std::string& problem() const { return problem_; }
  const std::string& fix() const { return fix_; }

 private:
  std::string file_;
  long line_, column_, field_;
  std::string problem_, fix_;
};

struct CsvRow {
  long line = 0;                    // 1-based line in the file
  std::vector<std::string> fields;  // unquoted and trimmed
  std::vector<long> columns;        // 1-based character column where each field starts
};

struct CsvComment {
  long line = 0;
  std::string text;  // the line without its leading '#'
};

enum class CsvHeader {
  required,  // the first row names the columns
  optional,  // the first row is a header when one of its fields is not a number (packings, PSD)
};

class CsvTable {
 public:
  static CsvTable read(const std::filesystem::path& file, CsvHeader header = CsvHeader::required);
  // `origin` names the text in errors (a file name).
  static CsvTable parse(std::string_view text, const std::string& origin, CsvHeader header = CsvHeader::required);

  const std::string& file() const { return file_; }
  char separator() const { return separator_; }
  bool decimal_comma() const { return separator_ != ','; }
  const std::vector<std::string>& header() const { return header_; }  // empty without a header row
  long header_line() const { return header_line_; }
  const std::vector<long>& header_columns() const { return header_columns_; }  // where each name starts
  // The units row's text per column ("" for a column without one); empty when there is no row.
  const std::vector<std::string>& units() const { return units_; }
  const std::vector<CsvRow>& rows() const { return rows_; }
  const std::vector<CsvComment>& comments() const { return comments_; }

  std::optional<std::size_t> find(const std::string& name) const;  // 0-based column
  // The value as a finite number, times the factor of the column's unit to SI (1 without a units
  // row). Errors name the cell and use `meaning` ("force in N") in the fix.
  double number(const CsvRow& row, std::size_t column, const std::string& meaning) const;
  // The column's factor to SI from the units row (1 without one).
  double si_factor(std::size_t column) const;
  [[noreturn]] void fail(const CsvRow& row, std::size_t column, const std::string& problem,
                         const std::string& fix) const;

 private:
  std::string file_;
  char separator_ = ',';
  std::vector<std::string> header_;
  long header_line_ = 0;
  std::vector<long> header_columns_;
  std::vector<std::string> units_;
  std::vector<double> factors_;
  std::vector<CsvRow> rows_;
  std::vector<CsvComment> comments_;

  void take_units_row();
};

// A plain number, or with decimal_comma also "1,25"; nullopt for anything else (empty text, units,
// "nan", "inf", thousands separators).
std::optional<double> parse_csv_number(std::string_view text, bool decimal_comma);

}  // namespace shard::io
