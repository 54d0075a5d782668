#pragma once
// A plugin parameter's type, default and range as a scene writes them: one spelling for
// `shard plugins` and the generated scene reference (`shard schema`).
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <type_traits>
#include <variant>

#include "shard/params.hpp"

namespace shard {

inline std::string param_type_text(ParamType t) {
  switch (t) {
    case ParamType::Number: return "number";
    case ParamType::Integer: return "integer";
    case ParamType::Boolean: return "bool";
    case ParamType::String: return "string";
    case ParamType::Vector3: return "vec3";
  }
  return "?";
}

inline std::string param_default_text(const ParamSpec& s) {
  return std::visit(
      [](const auto& d) -> std::string {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, std::monostate>) return "(required)";
        else if constexpr (std::is_same_v<T, double>) return fmt::format("{}", d);
        else if constexpr (std::is_same_v<T, bool>) return d ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>) return "\"" + d + "\"";
        else return fmt::format("[{}, {}, {}]", d[0], d[1], d[2]);
      },
      s.default_value);
}

// "[0, 10]", "(0, inf)", or "" for a parameter without bounds (strings, flags, vectors).
inline std::string param_range_text(const ParamSpec& s) {
  if (std::isinf(s.min) && std::isinf(s.max)) return "";
  const auto bound = [](double v) { return std::isinf(v) ? std::string(v < 0 ? "-inf" : "inf") : fmt::format("{}", v); };
  return fmt::format("{}{}, {}{}", s.min_exclusive || std::isinf(s.min) ? "(" : "[", bound(s.min), bound(s.max),
                     std::isinf(s.max) ? ")" : "]");
}

inline std::string param_scope_text(ParamScope scope) {
  switch (scope) {
    case ParamScope::Model: return "";
    case ParamScope::Material: return "per [[material]]";
    case ParamScope::Pair: return "per [[material_pair]]";
  }
  return "";
}

}  // namespace shard
