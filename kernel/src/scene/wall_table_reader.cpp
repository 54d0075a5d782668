#include "wall_table_reader.hpp"

#include <fmt/format.h>

#include <optional>
#include <string>

#include "shard/io/csv.hpp"
#include "shard/scene.hpp"

namespace shard {
namespace {

// The names a table may use: time and either a position (displacement, angle) or a rate.
struct TableNames {
  std::string key, position, rate, position_unit, rate_unit;
};

TableNames names_of(WallTableKind kind) {
  if (kind == WallTableKind::Rotation) return {"rotation_table", "angle", "angular_velocity", "rad", "rad/s"};
  return {"motion_table", "displacement", "velocity", "m", "m/s"};
}

struct TableColumns {
  std::size_t time = 0, value = 0;
  bool gives_velocity = false;
};

TableColumns find_columns(const io::CsvTable& t, const TableNames& n) {
  std::optional<std::size_t> time, value;
  TableColumns out;
  for (std::size_t c = 0; c < t.header().size(); ++c) {
    const std::string& h = t.header()[c];
    const long at = t.header_columns()[c];
    if (h == "time") {
      time = c;
    } else if (h == n.position || h == n.rate) {
      if (value)
        throw SceneError(fmt::format("{}:{}:{}: the {} names both {} and {}; give one of them", t.file(),
                                     t.header_line(), at, n.key, n.position, n.rate));
      value = c;
      out.gives_velocity = h == n.rate;
    } else {
      throw SceneError(fmt::format("{}:{}:{}: unknown column '{}' in the {}; the columns are time [s] and either "
                                   "{} [{}] or {} [{}]",
                                   t.file(), t.header_line(), at, h, n.key, n.position, n.position_unit, n.rate,
                                   n.rate_unit));
    }
  }
  if (!time || !value)
    throw SceneError(fmt::format("{}:{}:1: the {}'s header must name time and either {} or {}, e.g. 'time,{}'",
                                 t.file(), t.header_line(), n.key, n.position, n.rate, n.position));
  out.time = *time, out.value = *value;
  return out;
}

double cell_number(const io::CsvTable& t, const io::CsvRow& row, std::size_t c) {
  if (const auto v = io::parse_csv_number(row.fields[c], t.decimal_comma())) return *v * t.si_factor(c);
  throw SceneError(fmt::format("{}:{}:{}: '{}' is not a number", t.file(), row.line, row.columns[c], row.fields[c]));
}

}  // namespace

// The table is read by the one CSV reader (shard/io/csv.hpp): ',' or ';' or tab, decimal commas,
// a units row ("s;mm") applied to SI.
WallTable read_wall_table(const std::filesystem::path& file, WallTableKind kind) {
  const TableNames n = names_of(kind);
  if (!std::filesystem::is_regular_file(file))
    throw SceneError(fmt::format("{}: cannot open the wall's {} (a CSV of time and {} or {}); check the path, which "
                                 "is relative to the scene file",
                                 file.string(), n.key, n.position, n.rate));
  const io::CsvTable t = [&] {
    try {
      return io::CsvTable::read(file);
    } catch (const io::CsvError& e) {
      throw SceneError(fmt::format("{} (the wall's {}: a header 'time,{}' and one row per instant)", e.what(), n.key,
                                   n.position));
    }
  }();
  const TableColumns columns = find_columns(t, n);
  WallTable table;
  table.file = file.string();
  table.gives_velocity = columns.gives_velocity;
  long last_line = 0;
  for (const auto& row : t.rows()) {
    const double time = cell_number(t, row, columns.time), value = cell_number(t, row, columns.value);
    const long at = row.columns[columns.time];
    if (table.time.empty() && time != 0.0)
      throw SceneError(fmt::format("{}:{}:{}: the first time is {} s; the table must start at time 0 (the start of "
                                   "the run)",
                                   t.file(), row.line, at, time));
    if (!table.time.empty() && !(time > table.time.back()))
      throw SceneError(fmt::format("{}:{}:{}: time {} s is not later than {} s on line {}; the times must increase "
                                   "strictly",
                                   t.file(), row.line, at, time, table.time.back(), last_line));
    table.time.push_back(time);
    table.value.push_back(value);
    last_line = row.line;
  }
  try {
    prepare_wall_table(table);
  } catch (const std::invalid_argument& e) {
    throw SceneError(e.what());
  }
  return table;
}

}  // namespace shard
