#pragma once
// Parameter schemas: each plugin declares what it reads from the scene, with unit, range and the
// neutral value at which its extra physical effect is off (used by `shard diagnose`).
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "shard/types.hpp"

namespace shard {

enum class ParamType { Number, Integer, Boolean, String, Vector3 };

// Where a contact law's parameter is given in a scene with several materials (docs/reference/materials.md):
// once in [contact] (Model), per [[material]] (Material, e.g. a modulus), or per
// [[material_pair]] (Pair, e.g. friction). With one material all come from [contact].
enum class ParamScope { Model, Material, Pair };

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Number;
  std::string unit;  // SI unit, "1" for dimensionless, "" for strings and flags
  std::string doc;   // one line
  // Default as it would be written in a scene; std::monostate means "required".
  std::variant<std::monostate, double, bool, std::string, Vec3> default_value;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;  // e.g. a modulus must be > 0, not >= 0
  std::optional<double> neutral;  // value at which this parameter's effect is off
  ParamScope scope = ParamScope::Model;
};

using ParamValue = std::variant<double, bool, std::string, Vec3>;

// Validated parameter values of one plugin instance (defaults filled in).
class ParamSet {
 public:
  void set(const std::string& name, ParamValue value) { values_[name] = std::move(value); }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  double number(const std::string& name) const { return get<double>(name); }
  long integer(const std::string& name) const { return static_cast<long>(get<double>(name)); }
  bool flag(const std::string& name) const { return get<bool>(name); }
  const std::string& text(const std::string& name) const { return get<std::string>(name); }
  const Vec3& vec3(const std::string& name) const { return get<Vec3>(name); }
  // A text parameter listing names separated by commas and/or blanks, as `effects` does; empty
  // when the parameter is not set.
  std::vector<std::string> names(const std::string& name) const {
    std::vector<std::string> out;
    if (!has(name)) return out;
    std::string word;
    for (const char c : text(name) + ",") {
      if (c == ',' || c == ' ' || c == '\t') {
        if (!word.empty()) out.push_back(word);
        word.clear();
      } else {
        word += c;
      }
    }
    return out;
  }
  const std::map<std::string, ParamValue>& all() const { return values_; }

 private:
  template <class T>
  const T& get(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end()) throw std::out_of_range("parameter '" + name + "' is not set");
    if (auto* v = std::get_if<T>(&it->second)) return *v;
    throw std::invalid_argument("parameter '" + name + "' has another type");
  }
  std::map<std::string, ParamValue> values_;
};

}  // namespace shard
