// Load curves as CSV: the run's <stem>_curve.csv, a lab measurement, or the report's own copy.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "shard/bending/curve_analysis.hpp"
#include "shard/io/csv.hpp"
#include "shard/io/units.hpp"

namespace shard::bending {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// The first column whose name starts with one of `prefixes` (lower case; the names of Shard's own
// files and of Zwick and Instron exports).
std::optional<std::size_t> find_column(const io::CsvTable& t, std::initializer_list<const char*> prefixes) {
  for (std::size_t c = 0; c < t.header().size(); ++c)
    for (const char* p : prefixes)
      if (lower(t.header()[c]).rfind(p, 0) == 0) return c;
  return std::nullopt;
}

}  // namespace

analysis::LoadCurve read_curve_csv(const std::string& path) {
  const auto t = io::CsvTable::read(path);
  const auto cw = find_column(t, {"displacement", "deflection", "w", "standardweg", "extension", "deformation"});
  const auto cf = find_column(t, {"force", "load", "f", "standardkraft", "kraft"});
  const auto ct = find_column(t, {"time", "t_", "prüfzeit", "zeit"});
  if (!cw || !cf)
    throw std::runtime_error(fmt::format("{}:{}: the header needs a displacement column (displacement..., w..., "
                                         "Standardweg, Extension) and a force column (force..., F..., Standardkraft, "
                                         "Load)",
                                         path, t.header_line()));
  // A units row converts each value to SI itself; without one, a unit in the name does (force_kN).
  auto factor = [&](std::size_t c) { return t.units().empty() ? io::split_unit_from_name(t.header()[c]).factor : 1.0; };
  analysis::LoadCurve curve;
  for (const auto& row : t.rows()) {
    curve.displacement.push_back(factor(*cw) * t.number(row, *cw, "displacement"));
    curve.force.push_back(factor(*cf) * t.number(row, *cf, "force"));
    if (ct) curve.time.push_back(factor(*ct) * t.number(row, *ct, "time"));
  }
  if (curve.force.empty()) throw std::runtime_error(fmt::format("{}: no data rows", path));
  return curve;
}

std::map<std::string, std::string> read_curve_metadata(const std::string& path) {
  std::map<std::string, std::string> out;
  const auto table = io::CsvTable::read(path);
  for (const auto& comment : table.comments()) {
    if (!comment.text.starts_with('!')) continue;
    const auto eq = comment.text.find('=');
    if (eq == std::string::npos)
      throw std::runtime_error(
          fmt::format("{}:{}: a '#!' line is 'key = value', e.g. '#! span_mm = 180'", path, comment.line));
    out[trim(comment.text.substr(1, eq - 1))] = trim(comment.text.substr(eq + 1));
  }
  return out;
}

void write_curve_csv(const std::string& path, const analysis::LoadCurve& curve) {
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
