#pragma once
// A table of named columns (numbers or text), written the same way as CSV (one header line, full
// precision) and as an HDF5 group (one dataset per column, the notes as string attributes).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "shard/run_file.hpp"

namespace shard::analysis {

struct Column {
  std::string name;  // with its unit where it has one: "impact_speed_m_s", "x50_m"
  std::variant<std::vector<double>, std::vector<std::int64_t>, std::vector<std::string>> values;
  std::size_t size() const;
};

struct ColumnTable {
  std::vector<Column> columns;
  std::vector<std::pair<std::string, std::string>> notes;  // (name, text): method, confidence level

  ColumnTable& add(std::string name, std::vector<double> values);
  ColumnTable& add(std::string name, std::vector<std::int64_t> values);
  ColumnTable& add(std::string name, std::vector<std::string> values);
  ColumnTable& note(std::string name, std::string text);
  // Rows of the first column; throws std::invalid_argument when the columns differ in length.
  std::size_t rows() const;
};

// CSV: the header, then one line per row; numbers with 17 significant digits, text quoted when it
// holds a comma, a quote or a line break. Throws std::runtime_error when the file cannot be written.
void write_csv(const ColumnTable& table, const std::filesystem::path& file);

// The table as the kernel's table writer takes it (shard/run_file.hpp): a dataset per column
// (text as variable-length UTF-8), the row count as the attribute `rows`, the notes as string
// attributes.
RunTable to_run_table(const ColumnTable& table);

// Replaces the group `group` ("/a/b": parents are created) of the HDF5 file `file` (created when
// absent) with to_run_table(table). Throws OutputError naming the file.
void write_hdf5_table(const std::filesystem::path& file, const std::string& group, const ColumnTable& table);

}  // namespace shard::analysis
