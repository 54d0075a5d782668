#pragma once
// Units as lab machines write them in a units row or a column name ("mm", "[kN]", "(MPa)",
// "N/mm²", "mm/min"), each with its factor to SI.
#include <optional>
#include <string_view>

namespace shard::io {

// The factor that turns a value in `unit` into SI (mm -> 1e-3, kN -> 1e3, min -> 60, % -> 0.01);
// brackets and spaces around the unit are ignored; nullopt when the unit is not known.
std::optional<double> si_factor_of_unit(std::string_view unit);

}  // namespace shard::io
