#pragma once
// Reading one TOML section of a scene against a fixed list of keys (scene_loader.cpp and
// body_section.cpp share it): every getter records its key as known, finish() refuses the
// rest with file:line:column, the key and the closest valid key.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>
#include <toml++/toml.h>

#include "shard/scene.hpp"

namespace shard::scene_detail {

// A node with no source position was put there by an override (--set, a sweep, an assumption),
// so pointing at line 0 of the file would send the user looking in the wrong place.
inline std::string where(const std::string& file, const toml::source_region& s) {
  if (s.begin.line == 0) return fmt::format("{} (a value given by --set, not in the file)", file);
  return fmt::format("{}:{}:{}", file, s.begin.line, s.begin.column);
}

// Reads one section against a fixed list of keys; every getter records the key as known.
class Section {
 public:
  Section(const toml::table* t, std::string file, std::string name)
      : table_(t), file_(std::move(file)), name_(std::move(name)) {}
  bool present() const { return table_ != nullptr; }
  // A key read elsewhere (a sub-table such as [body.generator]): not refused by finish().
  void allow(const std::string& key) { known_.push_back(key); }
  std::string at() const { return table_ ? where(file_, table_->source()) : file_; }
  std::string at(const std::string& key) const {
    const toml::node* n = table_ ? table_->get(key) : nullptr;
    return n ? where(file_, n->source()) : at();
  }

  double number(const std::string& key, double fallback, double min = -1e300, double max = 1e300,
                const char* unit = "") {
    known_.push_back(key);
    const toml::node* n = node(key);
    if (!n) return fallback;
    auto v = n->value<double>();
    if (!v) fail(key, fmt::format("must be a number [{}]", unit));
    if (!(*v >= min && *v <= max)) fail(key, fmt::format("= {} is out of range [{}, {}] {}", *v, min, max, unit));
    return *v;
  }
  bool flag(const std::string& key, bool fallback) {
    known_.push_back(key);
    const toml::node* n = node(key);
    if (!n) return fallback;
    auto v = n->value<bool>();
    if (!v) fail(key, "must be true or false");
    return *v;
  }
  std::string text(const std::string& key, const std::string& fallback) {
    known_.push_back(key);
    const toml::node* n = node(key);
    if (!n) return fallback;
    auto v = n->value<std::string>();
    if (!v) fail(key, "must be a string");
    return *v;
  }
  Vec3 vec3(const std::string& key, const Vec3& fallback) {
    known_.push_back(key);
    const toml::node* n = node(key);
    if (!n) return fallback;
    return to_vec3(*n, key);
  }
  std::vector<std::string> strings(const std::string& key) {
    known_.push_back(key);
    std::vector<std::string> out;
    const toml::node* n = node(key);
    if (!n) return out;
    const auto* arr = n->as_array();
    if (!arr) fail(key, "must be an array of strings, e.g. [\"pin_left\", \"pin_right\"]");
    for (const auto& e : *arr) {
      auto s = e.value<std::string>();
      if (!s) fail(key, "must be an array of strings");
      out.push_back(*s);
    }
    return out;
  }
  // "auto" or a number.
  double number_or_auto(const std::string& key) {
    known_.push_back(key);
    const toml::node* n = node(key);
    if (!n) return 0;
    if (auto s = n->value<std::string>(); s && *s == "auto") return 0;
    auto v = n->value<double>();
    if (!v || !(*v > 0)) fail(key, "must be \"auto\" or a positive number of seconds");
    return *v;
  }
  Vec3 to_vec3(const toml::node& n, const std::string& key) const {
    const auto* arr = n.as_array();
    if (!arr || arr->size() != 3) fail(key, "must be an array of three numbers, e.g. [0, 0, -9.81]");
    Vec3 v;
    for (int c = 0; c < 3; ++c) {
      auto d = (*arr)[static_cast<std::size_t>(c)].value<double>();
      if (!d) fail(key, "must be an array of three numbers");
      v[c] = *d;
    }
    return v;
  }
  // Everything not read by a getter is a plugin parameter (when `rest` is given) or an error.
  void finish(std::map<std::string, RawParam>* rest = nullptr) const {
    if (!table_) return;
    for (auto&& [k, v] : *table_) {
      const std::string key(k.str());
      if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
      if (rest) {
        (*rest)[key] = RawParam{plugin_value(v, key), where(file_, v.source())};
        continue;
      }
      const std::string hint = closest_match(key, known_);
      throw SceneError(fmt::format("{}: unknown key '{}' in [{}]{}; valid keys: {}", where(file_, v.source()), key,
                                   name_, hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                                   fmt::join(known_, ", ")));
    }
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw SceneError(fmt::format("{}: [{}] {} {}", at(key), name_, key, what));
  }

 private:
  const toml::node* node(const std::string& key) const { return table_ ? table_->get(key) : nullptr; }
  ParamValue plugin_value(const toml::node& n, const std::string& key) const {
    if (auto d = n.value<double>()) return *d;
    if (auto b = n.value<bool>()) return *b;
    if (auto s = n.value<std::string>()) return *s;
    if (n.is_array()) return to_vec3(n, key);
    fail(key, "has a type no plugin parameter takes (number, boolean, string or [x, y, z])");
  }
  const toml::table* table_;
  std::string file_;
  std::string name_;
  std::vector<std::string> known_;
};

// The plugin named by `plugin = "..."` in `table` (a section called `name` in messages), its
// other keys validated as the plugin's parameters.
PluginChoice plugin_choice(const toml::table* table, const std::string& file, const std::string& name,
                           PluginKind kind, const PluginHost& host);

}  // namespace shard::scene_detail
