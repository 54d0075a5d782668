#include "shard/io/csv.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "shard/io/units.hpp"

namespace shard::io {
namespace {

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

// ';' when the line has one outside quotes, else a tab, else ','.
char sniff_separator(std::string_view line) {
  bool quoted = false, tab = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == ';') return ';';
    tab = tab || c == '\t';
  }
  return tab ? '\t' : ',';
}

// One quoted field starting at line[pos] == '"': its text ("" is a quote) and the position after
// the closing quote.
std::pair<std::string, std::size_t> quoted_field(std::string_view line, std::size_t pos, const std::string& origin,
                                                 long line_no, long field) {
  std::string text;
  for (std::size_t k = pos + 1; k < line.size(); ++k) {
    if (line[k] != '"') {
      text += line[k];
    } else if (k + 1 < line.size() && line[k + 1] == '"') {
      text += '"', ++k;
    } else {
      return {text, k + 1};
    }
  }
  throw CsvError(origin, line_no, static_cast<long>(pos + 1), field, "the quote that opens this field is not closed",
                 "close the field with a '\"' on the same line (a quote inside a field is written \"\")");
}

CsvRow split_fields(std::string_view line, char separator, const std::string& origin, long line_no) {
  CsvRow row;
  row.line = line_no;
  std::size_t pos = 0;
  while (true) {
    while (pos < line.size() && line[pos] != separator && is_blank(line[pos])) ++pos;
    row.columns.push_back(static_cast<long>(pos + 1));
    const auto field = static_cast<long>(row.fields.size() + 1);
    std::size_t end = line.find(separator, pos);
    if (pos < line.size() && line[pos] == '"') {
      auto [text, after] = quoted_field(line, pos, origin, line_no, field);
      end = line.find(separator, after);
      if (!trim(line.substr(after, end == std::string_view::npos ? std::string_view::npos : end - after)).empty())
        throw CsvError(origin, line_no, static_cast<long>(after + 1), field, "text follows the closing quote",
                       "put the whole field inside the quotes");
      row.fields.push_back(std::move(text));
    } else {
      row.fields.emplace_back(trim(line.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos)));
    }
    if (end == std::string_view::npos) return row;
    pos = end + 1;
  }
}

bool all_numbers(const CsvRow& row, bool decimal_comma) {
  return std::all_of(row.fields.begin(), row.fields.end(),
                     [&](const std::string& f) { return parse_csv_number(f, decimal_comma).has_value(); });
}

void check_header(const CsvRow& header, const std::string& origin) {
  for (std::size_t c = 0; c < header.fields.size(); ++c) {
    const auto field = static_cast<long>(c + 1);
    if (header.fields[c].empty())
      throw CsvError(origin, header.line, header.columns[c], field, "the header has an empty column name",
                     "name every column or remove the trailing separator");
    for (std::size_t d = 0; d < c; ++d)
      if (header.fields[d] == header.fields[c])
        throw CsvError(origin, header.line, header.columns[c], field,
                       fmt::format("column '{}' appears twice in the header", header.fields[c]),
                       "keep one column of each name");
  }
}

}  // namespace

CsvError::CsvError(std::string file, long line, long column, long field, std::string problem, std::string fix)
    : std::runtime_error(fmt::format("{}:{}:{}: {}; {}", file, line, column, problem, fix)),
      file_(std::move(file)), line_(line), column_(column), field_(field), problem_(std::move(problem)),
      fix_(std::move(fix)) {}

std::optional<double> parse_csv_number(std::string_view text, bool decimal_comma) {
  std::string buffer(text.substr(!text.empty() && text.front() == '+' ? 1 : 0));
  if (decimal_comma && buffer.find(',') != std::string::npos) {
    if (buffer.find('.') != std::string::npos || std::count(buffer.begin(), buffer.end(), ',') > 1)
      return std::nullopt;  // a thousands separator: ambiguous
    std::replace(buffer.begin(), buffer.end(), ',', '.');
  }
  double value = 0;
  const char* end = buffer.data() + buffer.size();
  const auto [ptr, ec] = std::from_chars(buffer.data(), end, value);
  if (buffer.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

CsvTable CsvTable::read(const std::filesystem::path& file, CsvHeader header) {
  std::ifstream in(file, std::ios::binary);
  if (!in || std::filesystem::is_directory(file))
    throw CsvError(file.string(), 0, 0, 0, "the file cannot be opened", "check the path");
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), file.string(), header);
}

CsvTable CsvTable::parse(std::string_view text, const std::string& origin, CsvHeader header) {
  CsvTable t;
  t.file_ = origin;
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  bool sniffed = false, header_open = header == CsvHeader::required;
  long line_no = 0;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t newline = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, newline - start);
    start = newline + 1, ++line_no;
    const std::string_view content = trim(line);
    if (content.empty()) continue;
    if (content.front() == '#') {
      t.comments_.push_back({line_no, std::string(content.substr(1))});
      continue;
    }
    if (!sniffed) t.separator_ = sniff_separator(line), sniffed = true;
    CsvRow row = split_fields(line.back() == '\r' ? line.substr(0, line.size() - 1) : line, t.separator_, origin,
                              line_no);
    if (t.header_line_ == 0 && t.rows_.empty() && (header_open || !all_numbers(row, t.decimal_comma()))) {
      check_header(row, origin);
      t.header_ = std::move(row.fields);
      t.header_columns_ = std::move(row.columns);
      t.header_line_ = line_no;
      continue;
    }
    header_open = false;
    const std::size_t expected = t.header_.empty() ? t.rows_.empty() ? row.fields.size() : t.rows_[0].fields.size()
                                                   : t.header_.size();
    if (row.fields.size() != expected) {
      const std::size_t at = std::min(row.fields.size(), expected);
      throw CsvError(origin, line_no, at < row.columns.size() ? row.columns[at] : static_cast<long>(line.size() + 1),
                     static_cast<long>(at + 1),
                     fmt::format("the line has {} fields but {} has {}{}", row.fields.size(),
                                 t.header_.empty() ? "the first row" : "the header", expected,
                                 t.header_.empty() ? "" : fmt::format(" ({})", fmt::join(t.header_, ","))),
                     fmt::format("write one value per column, separated by '{}' (an empty value is just two "
                                 "separators)",
                                 t.separator_ == '\t' ? std::string("tab") : std::string(1, t.separator_)));
    }
    t.rows_.push_back(std::move(row));
  }
  if (t.header_.empty() && t.rows_.empty())
    throw CsvError(origin, 0, 0, 0, "the file is empty (no header line and no rows)",
                   "start the file with a header line naming the columns, then one row per line");
  t.take_units_row();
  return t;
}

// The first row after the header is a units row when every non-empty field is a known unit.
void CsvTable::take_units_row() {
  factors_.assign(header_.empty() ? 0 : header_.size(), 1.0);
  if (header_.empty() || rows_.empty()) return;
  const auto& first = rows_.front().fields;
  bool any = false;
  for (std::size_t c = 0; c < first.size(); ++c) {
    if (first[c].empty()) continue;
    const auto factor = si_factor_of_unit(first[c]);
    if (!factor || parse_csv_number(first[c], decimal_comma())) return;  // "1" is a number in a data row
    factors_[c] = *factor, any = true;
  }
  if (!any) return;
  units_ = first;
  rows_.erase(rows_.begin());
}

std::optional<std::size_t> CsvTable::find(const std::string& name) const {
  const auto it = std::find(header_.begin(), header_.end(), name);
  if (it == header_.end()) return std::nullopt;
  return static_cast<std::size_t>(it - header_.begin());
}

double CsvTable::si_factor(std::size_t column) const { return column < factors_.size() ? factors_[column] : 1.0; }

void CsvTable::fail(const CsvRow& row, std::size_t column, const std::string& problem, const std::string& fix) const {
  throw CsvError(file_, row.line, column < row.columns.size() ? row.columns[column] : 0, static_cast<long>(column + 1),
                 problem, fix);
}

double CsvTable::number(const CsvRow& row, std::size_t column, const std::string& meaning) const {
  const std::string& s = row.fields.at(column);
  if (const auto value = parse_csv_number(s, decimal_comma())) return *value * si_factor(column);
  // Only a field that is not a number needs its column named (large tables read millions of numbers).
  const std::string name = column < header_.size() ? fmt::format("column '{}'", header_[column])
                                                   : fmt::format("field {}", column + 1);
  if (s.empty()) fail(row, column, fmt::format("{} is empty", name), fmt::format("write the {}", meaning));
  std::string lower(s);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower.find("nan") != std::string::npos)
    fail(row, column, fmt::format("{} is NaN", name),
         "remove the row or replace the NaN by the measured value (a gap in the recording is better left out than "
         "filled)");
  if (lower.find("inf") != std::string::npos)
    fail(row, column, fmt::format("{} is infinite", name), "write a finite value or remove the row");
  fail(row, column, fmt::format("{} is '{}', not a number", name, s),
       fmt::format("write the {} as a plain number ({}no unit, no thousands separator)", meaning,
                   decimal_comma() ? "decimal point or comma, " : "decimal point, "));
}

}  // namespace shard::io
