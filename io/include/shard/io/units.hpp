#pragma once
// Units as lab machines write them in a units row or a column name ("mm", "[kN]", "(MPa)",
// "N/mm²", "mm/min"), each with its factor to SI.
#include <optional>
#include <string>
#include <string_view>

namespace shard::io {

// The factor that turns a value in `unit` into SI (mm -> 1e-3, kN -> 1e3, min -> 60, % -> 0.01);
// brackets and spaces around the unit are ignored; nullopt when the unit is not known.
std::optional<double> si_factor_of_unit(std::string_view unit);

// A column name that carries its unit, after its last '_' or in brackets at its end ("time_s",
// "force_kN", "force [kN]", "w (mm)"): the quantity's name and the unit's factor to SI. A name
// without a known unit there is the whole name, with factor 1 and no unit.
struct NameWithUnit {
  std::string name;
  double factor = 1;
  bool has_unit = false;
};
NameWithUnit split_unit_from_name(std::string_view column);

}  // namespace shard::io
