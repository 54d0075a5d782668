#include "wall_table_reader.hpp"

#include <fmt/format.h>

#include <charconv>
#include <fstream>
#include <string>
#include <vector>

#include "shard/scene.hpp"

namespace shard {
namespace {

struct Cell {
  std::string text;
  std::size_t column = 1;  // 1-based character column of the cell's start
};

std::vector<Cell> split_row(const std::string& line) {
  std::vector<Cell> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string raw = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    std::size_t lead = raw.find_first_not_of(" \t\r");
    const std::size_t trail = raw.find_last_not_of(" \t\r");
    if (lead == std::string::npos) lead = 0;
    cells.push_back({trail == std::string::npos ? std::string() : raw.substr(lead, trail - lead + 1), start + lead + 1});
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

}  // namespace

WallTable read_wall_table(const std::filesystem::path& file, WallTableKind kind) {
  const std::string name = file.string();
  const bool turns = kind == WallTableKind::Rotation;
  // The value column's two names: a position (displacement, angle) or a rate.
  const std::string position = turns ? "angle" : "displacement", rate = turns ? "angular_velocity" : "velocity";
  const std::string key = turns ? "rotation_table" : "motion_table";
  std::ifstream in(file);
  if (!in)
    throw SceneError(fmt::format("{}: cannot open the wall's {} (a CSV of time and {} or {}); check the path, which "
                                 "is relative to the scene file",
                                 name, key, position, rate));
  WallTable table;
  table.file = name;
  int time_col = -1, value_col = -1;
  std::size_t columns = 0;
  std::string line;
  int line_no = 0, last_line = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const std::vector<Cell> cells = split_row(line);
    if (columns == 0) {  // the header
      columns = cells.size();
      for (std::size_t c = 0; c < cells.size(); ++c) {
        const std::string& h = cells[c].text;
        if (h == "time") time_col = static_cast<int>(c);
        else if (h == position || h == rate) {
          if (value_col >= 0)
            throw SceneError(fmt::format("{}:{}:{}: the {} names both {} and {}; give one of them", name, line_no,
                                         cells[c].column, key, position, rate));
          value_col = static_cast<int>(c);
          table.gives_velocity = h == rate;
        } else {
          throw SceneError(fmt::format("{}:{}:{}: unknown column '{}' in the {}; the columns are time [s] and either "
                                       "{} [{}] or {} [{}]",
                                       name, line_no, cells[c].column, h, key, position, turns ? "rad" : "m", rate,
                                       turns ? "rad/s" : "m/s"));
        }
      }
      if (time_col < 0 || value_col < 0)
        throw SceneError(fmt::format("{}:{}:1: the {}'s header must name time and either {} or {}, e.g. 'time,{}'",
                                     name, line_no, key, position, rate, position));
      continue;
    }
    if (cells.size() != columns)
      throw SceneError(fmt::format("{}:{}:1: {} cells where the header has {}", name, line_no, cells.size(), columns));
    double v[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      const Cell& cell = cells[static_cast<std::size_t>(k == 0 ? time_col : value_col)];
      const char* end = cell.text.data() + cell.text.size();
      const auto r = std::from_chars(cell.text.data(), end, v[k]);
      if (r.ec != std::errc() || r.ptr != end || cell.text.empty())
        throw SceneError(fmt::format("{}:{}:{}: '{}' is not a number", name, line_no, cell.column, cell.text));
    }
    if (table.time.empty() && v[0] != 0.0)
      throw SceneError(fmt::format("{}:{}:{}: the first time is {} s; the table must start at time 0 (the start of "
                                   "the run)",
                                   name, line_no, cells[static_cast<std::size_t>(time_col)].column, v[0]));
    if (!table.time.empty() && !(v[0] > table.time.back()))
      throw SceneError(fmt::format("{}:{}:{}: time {} s is not later than {} s on line {}; the times must increase "
                                   "strictly",
                                   name, line_no, cells[static_cast<std::size_t>(time_col)].column, v[0],
                                   table.time.back(), last_line));
    table.time.push_back(v[0]);
    table.value.push_back(v[1]);
    last_line = line_no;
  }
  if (columns == 0)
    throw SceneError(fmt::format("{}: the {} is empty; write a header 'time,{}' and rows", name, key, position));
  try {
    prepare_wall_table(table);
  } catch (const std::invalid_argument& e) {
    throw SceneError(e.what());
  }
  return table;
}

}  // namespace shard
