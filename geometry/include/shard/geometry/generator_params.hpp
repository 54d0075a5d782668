#pragma once
// Compact construction of the generator plugins' parameter schemas.
#include <limits>
#include <string>
#include <utility>

#include "shard/params.hpp"

namespace shard::geometry {

struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
};
inline constexpr Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};
inline constexpr Range kNonNegative{0.0, std::numeric_limits<double>::infinity(), false};

inline ParamSpec param(std::string name, ParamType type, std::string unit, std::string doc,
                       decltype(ParamSpec::default_value) default_value, Range range = {}) {
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = type;
  spec.unit = std::move(unit);
  spec.doc = std::move(doc);
  spec.default_value = std::move(default_value);
  spec.min = range.min;
  spec.max = range.max;
  spec.min_exclusive = range.min_exclusive;
  return spec;
}

}  // namespace shard::geometry
