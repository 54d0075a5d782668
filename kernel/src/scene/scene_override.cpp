#include "shard/scene_override.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <sstream>

#include "scene_override_toml.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

namespace shard {
namespace {

// The typed value of a parsed TOML node; throws for the shapes no scene key takes from --set.
SceneOverride::Value from_node(const toml::node& n, const std::string& assignment) {
  if (auto b = n.value_exact<bool>()) return *b;
  if (auto i = n.value_exact<std::int64_t>()) return *i;
  if (auto d = n.value_exact<double>()) return *d;
  if (auto s = n.value_exact<std::string>()) return *s;
  if (const auto* a = n.as_array()) {
    if (a->empty()) return std::vector<double>{};
    if (a->is_homogeneous<std::string>()) {
      std::vector<std::string> out;
      for (const auto& e : *a) out.push_back(*e.value<std::string>());
      return out;
    }
    std::vector<double> out;
    for (const auto& e : *a) {
      const auto d = e.value<double>();
      if (!d)
        throw SceneError(fmt::format("--set '{}': an array value must hold numbers or strings only", assignment));
      out.push_back(*d);
    }
    return out;
  }
  throw SceneError(fmt::format("--set '{}': a table value cannot be set from the command line; edit the scene file",
                               assignment));
}

toml::array numbers(const double* x, std::size_t n) {
  toml::array a;
  for (std::size_t k = 0; k < n; ++k) a.push_back(x[k]);
  return a;
}

void insert(toml::table& t, const std::string& key, const SceneOverride::Value& value) {
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, Vec3>) {
          t.insert_or_assign(key, numbers(v.data(), 3));
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          t.insert_or_assign(key, numbers(v.data(), v.size()));
        } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
          toml::array a;
          for (const auto& s : v) a.push_back(s);
          t.insert_or_assign(key, std::move(a));
        } else {
          t.insert_or_assign(key, v);
        }
      },
      value);
}

// The names of the [[material]] entries, quoted, for messages.
std::string material_names(const toml::array& materials) {
  std::string out;
  for (const auto& m : materials)
    if (const auto* t = m.as_table())
      out += fmt::format("{}'{}'", out.empty() ? "" : ", ", (*t)["name"].value_or(std::string()));
  return out;
}

// The [[material]] entries an override names, or a SceneError saying how the scene's materials are
// written instead.
toml::array& material_entries(toml::table& root, const SceneOverride& o) {
  if (auto* materials = root["material"].as_array()) return *materials;
  if (root["material"].as_table())
    throw SceneError(fmt::format("--set '{}': the scene has one [material] section, not [[material]] entries: set "
                                 "its density with material.density=..., its contact parameters with contact.KEY=... "
                                 "(docs/reference/materials.md)",
                                 o.text()));
  throw SceneError(fmt::format("--set '{}': the scene has no [[material]] entries (docs/reference/materials.md)", o.text()));
}

// A material's name and a pair's materials are how bodies, walls and rows find each other.
void refuse_identity_key(const SceneOverride& o, const std::string& key) {
  if (key == "name" || key == "materials")
    throw SceneError(fmt::format("--set '{}': '{}' names what the other entries refer to and cannot be set from the "
                                 "command line; edit the scene file",
                                 o.text(), key));
}

// material.NAME.key: a value of the [[material]] entry named NAME.
void apply_material(toml::table& root, const SceneOverride& o, const std::vector<std::string>& parts) {
  toml::array& materials = material_entries(root, o);
  refuse_identity_key(o, parts[2]);
  std::vector<std::string> names;
  for (auto& m : materials)
    if (auto* t = m.as_table()) {
      names.push_back((*t)["name"].value_or(std::string()));
      if (names.back() == parts[1]) {
        insert(*t, parts[2], o.value);
        return;
      }
    }
  const std::string hint = closest_match(parts[1], names);
  throw SceneError(fmt::format("--set '{}': no [[material]] named '{}'{}; the scene's materials: {}", o.text(),
                               parts[1], hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                               material_names(materials)));
}

// material_pair.A.B.key: a value of the [[material_pair]] row of materials A and B (either order),
// or of the default row with A = B = "*". A pair without its own row gets one holding just this
// key (its other parameters still come from the default row, key by key).
void apply_material_pair(toml::table& root, const SceneOverride& o, const std::vector<std::string>& parts) {
  toml::array& materials = material_entries(root, o);
  refuse_identity_key(o, parts[3]);
  const std::string &a = parts[1], &b = parts[2];
  if ((a == "*") != (b == "*"))
    throw SceneError(fmt::format("--set '{}': name two materials, e.g. material_pair.cake.steel.friction=0.3, or "
                                 "write material_pair.*.*.KEY for the default row",
                                 o.text()));
  if (a != "*") {
    std::vector<std::string> names;
    for (const auto& m : materials)
      if (const auto* t = m.as_table()) names.push_back((*t)["name"].value_or(std::string()));
    for (const std::string& name : {a, b})
      if (std::find(names.begin(), names.end(), name) == names.end()) {
        const std::string hint = closest_match(name, names);
        throw SceneError(fmt::format("--set '{}': no [[material]] named '{}'{}; the scene's materials: {}", o.text(),
                                     name, hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                                     material_names(materials)));
      }
  }
  if (!root["material_pair"].as_array()) {
    if (root.contains("material_pair")) return;  // not an array of tables: the loader says so with its line
    root.insert("material_pair", toml::array{});
  }
  toml::array& rows = *root["material_pair"].as_array();
  for (auto& row : rows) {
    auto* t = row.as_table();
    const auto* pair = t ? (*t)["materials"].as_array() : nullptr;
    if (!pair || pair->size() != 2) continue;
    const auto x = (*pair)[0].value<std::string>(), y = (*pair)[1].value<std::string>();
    if ((x == a && y == b) || (x == b && y == a)) {
      insert(*t, parts[3], o.value);
      return;
    }
  }
  toml::table row;
  row.insert("materials", toml::array{a, b});
  insert(row, parts[3], o.value);
  rows.push_back(std::move(row));
}

}  // namespace

SceneOverride SceneOverride::parse(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError(fmt::format("--set '{}': expected section.key=value, e.g. bond.youngs_modulus=13e6", assignment));
  const std::string text = assignment.substr(eq + 1);
  toml::table holder;
  try {
    holder = toml::parse("v = " + text);
  } catch (const toml::parse_error&) {
    return {assignment.substr(0, eq), text};  // bare words are strings: --set generator.file=beam.stl
  }
  return {assignment.substr(0, eq), from_node(*holder.get("v"), assignment)};
}

std::string SceneOverride::text() const {
  const std::string v = std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, bool>) return x ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>) return fmt::format("\"{}\"", x);
        else if constexpr (std::is_same_v<T, Vec3>) return fmt::format("[{}, {}, {}]", x[0], x[1], x[2]);
        else if constexpr (std::is_same_v<T, std::vector<std::string>>) return fmt::format("{}", x);
        else return fmt::format("{}", x);
      },
      value);
  return key + "=" + v;
}

SceneOverrides parse_overrides(const std::vector<std::string>& assignments) {
  SceneOverrides out;
  out.reserve(assignments.size());
  for (const auto& a : assignments) out.push_back(SceneOverride::parse(a));
  return out;
}

void apply_override(toml::table& root, const SceneOverride& o) {
  const std::vector<std::string> parts = scene_key_parts(o.key);
  if (parts.size() == 3 && parts[0] == "wall") {
    if (auto* walls = root["wall"].as_array())
      for (auto& w : *walls)
        if (auto* t = w.as_table(); t && (*t)["name"].value<std::string>() == parts[1]) {
          insert(*t, parts[2], o.value);
          return;
        }
    throw SceneError(fmt::format("--set '{}': no [[wall]] named '{}'", o.text(), parts[1]));
  }
  // body.NAME.key (placement) or body.NAME.generator.key / body.NAME.stream.key; NAME is the
  // entry's name, or body<k> for the k-th entry without one.
  if ((parts.size() == 3 || parts.size() == 4) && parts[0] == "body") {
    if (parts.size() == 4 && parts[2] != "generator" && parts[2] != "stream")
      throw SceneError(fmt::format("--set '{}': a body's tables are 'generator' and 'stream', e.g. "
                                   "body.{}.generator.diameter_min=0.004",
                                   o.text(), parts[1]));
    if (auto* bodies = root["body"].as_array()) {
      std::size_t k = 0;
      for (auto& b : *bodies) {
        auto* t = b.as_table();
        if (!t || (*t)["name"].value_or(fmt::format("body{}", k++)) != parts[1]) continue;
        toml::table* target = t;
        if (parts.size() == 4) {
          if (!(*t)[parts[2]].as_table()) t->insert_or_assign(parts[2], toml::table{});
          target = (*t)[parts[2]].as_table();
        }
        insert(*target, parts.back(), o.value);
        return;
      }
    }
    throw SceneError(fmt::format("--set '{}': no [[body]] named '{}'", o.text(), parts[1]));
  }
  if (parts.size() == 3 && parts[0] == "material" && root["material"].as_array()) {
    apply_material(root, o, parts);
    return;
  }
  if (parts.size() == 4 && parts[0] == "material_pair") {
    apply_material_pair(root, o, parts);
    return;
  }
  if (parts.size() == 3 && parts[0] == "material") material_entries(root, o);  // says how to set [material]
  if (parts.size() != 2 || parts[0].empty() || parts[1].empty())
    throw SceneError(fmt::format(
        "--set '{}': expected section.key=value (or wall.NAME.key=value, body.NAME.key=value, "
        "body.NAME.generator.key=value, body.NAME.stream.key=value, material.NAME.key=value, "
        "material_pair.NAME.NAME.key=value)",
        o.text()));
  // An array of entries ([[wall]], [[material]], ...) has no key of its own: name an entry.
  if (const auto* entries = root[parts[0]].as_array()) {
    if (parts[0] == "material")
      throw SceneError(fmt::format("--set '{}': the scene has [[material]] entries; name one: material.NAME.{}=... "
                                   "(the scene's materials: {})",
                                   o.text(), parts[1], material_names(*entries)));
    throw SceneError(fmt::format("--set '{}': [[{}]] is a list of entries; name one, e.g. {}.NAME.{}=...", o.text(),
                                 parts[0], parts[0], parts[1]));
  }
  auto* section = root[parts[0]].as_table();
  if (!section) {
    root.insert(parts[0], toml::table{});
    section = root[parts[0]].as_table();
  }
  insert(*section, parts[1], o.value);
}

std::vector<std::string> scene_key_parts(const std::string& key) {
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
  return parts;
}

}  // namespace shard
