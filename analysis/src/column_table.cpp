#include "shard/analysis/column_table.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

namespace shard::analysis {
namespace {

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string cell(const Column& c, std::size_t row) {
  return std::visit(
      [row](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::vector<double>>) return fmt::format("{:.17g}", v[row]);
        else if constexpr (std::is_same_v<T, std::vector<std::int64_t>>) return fmt::format("{}", v[row]);
        else return csv_text(v[row]);
      },
      c.values);
}

}  // namespace

std::size_t Column::size() const {
  return std::visit([](const auto& v) { return v.size(); }, values);
}

ColumnTable& ColumnTable::add(std::string name, std::vector<double> values) {
  columns.push_back({std::move(name), std::move(values)});
  return *this;
}
ColumnTable& ColumnTable::add(std::string name, std::vector<std::int64_t> values) {
  columns.push_back({std::move(name), std::move(values)});
  return *this;
}
ColumnTable& ColumnTable::add(std::string name, std::vector<std::string> values) {
  columns.push_back({std::move(name), std::move(values)});
  return *this;
}
ColumnTable& ColumnTable::note(std::string name, std::string text) {
  notes.emplace_back(std::move(name), std::move(text));
  return *this;
}

std::size_t ColumnTable::rows() const {
  if (columns.empty()) return 0;
  const std::size_t n = columns.front().size();
  for (const Column& c : columns)
    if (c.size() != n)
      throw std::invalid_argument(fmt::format("table column {} has {} rows, {} has {}", c.name, c.size(),
                                              columns.front().name, n));
  return n;
}

void write_csv(const ColumnTable& table, const std::filesystem::path& file) {
  const std::size_t rows = table.rows();
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? "," : "") << csv_text(table.columns[c].name);
  out << "\n";
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? "," : "") << cell(table.columns[c], r);
    out << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

RunTable to_run_table(const ColumnTable& table) {
  RunTable out;
  for (const Column& c : table.columns)
    std::visit([&](const auto& values) { out.columns.emplace_back(c.name, values); }, c.values);
  out.figures.emplace_back("rows", static_cast<std::int64_t>(table.rows()));
  for (const auto& [name, text] : table.notes) out.figures.emplace_back(name, text);
  return out;
}

void write_hdf5_table(const std::filesystem::path& file, const std::string& group, const ColumnTable& table) {
  write_table_file(file, group, to_run_table(table));
}

}  // namespace shard::analysis
