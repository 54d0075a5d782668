// Load curves as CSV: the run's <stem>_curve.csv, a lab measurement, or the report's own copy.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "shard/bending/curve_analysis.hpp"

namespace shard::bending {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\"");
  const auto e = s.find_last_not_of(" \t\r\"");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(trim(cell));
  return out;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The factor to SI from a column name's unit suffix.
double unit_factor(const std::string& name) {
  if (ends_with(name, "_mm") || ends_with(name, "[mm]")) return 1e-3;
  if (ends_with(name, "_kN") || ends_with(name, "[kN]")) return 1e3;
  return 1.0;
}

}  // namespace

Curve read_curve_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the load curve", path));
  std::string line;
  std::size_t line_no = 0;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    header = split(line);
    break;
  }
  if (header.empty()) throw std::runtime_error(fmt::format("{}: no header line", path));
  auto find = [&](std::initializer_list<const char*> prefixes) -> std::ptrdiff_t {
    for (std::size_t c = 0; c < header.size(); ++c)
      for (const char* p : prefixes)
        if (header[c].rfind(p, 0) == 0) return static_cast<std::ptrdiff_t>(c);
    return -1;
  };
  const auto cw = find({"displacement", "deflection", "w"});
  const auto cf = find({"force", "load", "F"});
  const auto ct = find({"time", "t_"});
  if (cw < 0 || cf < 0)
    throw std::runtime_error(fmt::format(
        "{}:{}: the header needs a displacement column (displacement..., w...) and a force column (force..., F...)",
        path, line_no));
  const double sw = unit_factor(header[static_cast<std::size_t>(cw)]);
  const double sf = unit_factor(header[static_cast<std::size_t>(cf)]);
  Curve c;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    const auto cells = split(line);
    auto value = [&](std::ptrdiff_t col) {
      const auto k = static_cast<std::size_t>(col);
      if (k >= cells.size()) throw std::runtime_error(fmt::format("{}:{}: too few columns", path, line_no));
      try {
        std::size_t used = 0;
        const double v = std::stod(cells[k], &used);
        if (used != cells[k].size()) throw std::invalid_argument(cells[k]);
        return v;
      } catch (const std::exception&) {
        throw std::runtime_error(fmt::format("{}:{}: '{}' is not a number", path, line_no, cells[k]));
      }
    };
    c.displacement.push_back(sw * value(cw));
    c.force.push_back(sf * value(cf));
    if (ct >= 0) c.time.push_back(value(ct));
  }
  if (c.force.empty()) throw std::runtime_error(fmt::format("{}: no data rows", path));
  return c;
}

std::map<std::string, std::string> read_curve_metadata(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the load curve", path));
  std::map<std::string, std::string> out;
  std::string line;
  for (std::size_t line_no = 1; std::getline(in, line); ++line_no) {
    const std::string t = trim(line);
    if (t.rfind("#!", 0) != 0) continue;
    const auto eq = t.find('=');
    if (eq == std::string::npos)
      throw std::runtime_error(fmt::format("{}:{}: a '#!' line is 'key = value', e.g. '#! span_mm = 180'", path, line_no));
    out[trim(t.substr(2, eq - 2))] = trim(t.substr(eq + 1));
  }
  return out;
}

void write_curve_csv(const std::string& path, const Curve& curve) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the load curve", path));
  const bool has_time = curve.time.size() == curve.force.size();
  out << (has_time ? "time_s," : "") << "displacement_m,force_N\n";
  for (std::size_t k = 0; k < curve.force.size(); ++k) {
    if (has_time) out << fmt::format("{:.9g},", curve.time[k]);
    out << fmt::format("{:.9g},{:.9g}\n", curve.displacement[k], curve.force[k]);
  }
}

}  // namespace shard::bending
