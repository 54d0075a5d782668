#include "shard/io/units.hpp"

#include <array>
#include <numbers>
#include <string>
#include <utility>

namespace shard::io {
namespace {

struct Unit {
  std::string_view name;
  double factor;
};

// What testing machines (Zwick testXpert, Instron Bluehill, ...) put in their units rows.
constexpr std::array kUnits{
    Unit{"m", 1},          Unit{"cm", 1e-2},     Unit{"mm", 1e-3},        Unit{"um", 1e-6},
    Unit{"µm", 1e-6},      Unit{"N", 1},         Unit{"kN", 1e3},         Unit{"mN", 1e-3},
    Unit{"s", 1},          Unit{"ms", 1e-3},     Unit{"min", 60},         Unit{"h", 3600},
    Unit{"Pa", 1},         Unit{"kPa", 1e3},     Unit{"MPa", 1e6},        Unit{"GPa", 1e9},
    Unit{"N/mm²", 1e6},    Unit{"N/mm^2", 1e6},  Unit{"N/mm2", 1e6},      Unit{"m/s", 1},
    Unit{"mm/s", 1e-3},    Unit{"mm/min", 1e-3 / 60}, Unit{"N/m", 1},     Unit{"N/mm", 1e3},
    Unit{"kg", 1},         Unit{"g", 1e-3},      Unit{"J", 1},            Unit{"mJ", 1e-3},
    Unit{"rad", 1},        Unit{"°", std::numbers::pi / 180}, Unit{"deg", std::numbers::pi / 180},
    Unit{"%", 1e-2},       Unit{"-", 1},
};

std::string_view strip(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::optional<double> si_factor_of_unit(std::string_view unit) {
  unit = strip(unit);
  if (unit.size() >= 2 && ((unit.front() == '[' && unit.back() == ']') || (unit.front() == '(' && unit.back() == ')')))
    unit = strip(unit.substr(1, unit.size() - 2));
  for (const auto& u : kUnits)
    if (u.name == unit) return u.factor;
  return std::nullopt;
}

NameWithUnit split_unit_from_name(std::string_view column) {
  column = strip(column);
  const bool bracketed = !column.empty() && (column.back() == ']' || column.back() == ')');
  const std::size_t cut = bracketed ? column.find_last_of(column.back() == ']' ? '[' : '(') : column.rfind('_');
  if (cut == std::string_view::npos || cut == 0) return {std::string(column), 1, false};
  const std::string_view unit = bracketed ? column.substr(cut) : column.substr(cut + 1);
  const std::optional<double> factor = si_factor_of_unit(unit);
  if (!factor) return {std::string(column), 1, false};
  return {std::string(strip(column.substr(0, cut))), *factor, true};
}

}  // namespace shard::io
