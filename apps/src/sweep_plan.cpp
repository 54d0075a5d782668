#include "sweep_plan.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <set>

#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

namespace shard {
namespace {

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return {};
  const auto b = s.find_last_not_of(" \t");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& s, char by) {
  std::vector<std::string> parts;
  std::size_t from = 0;
  for (std::size_t at = s.find(by); at != std::string::npos; at = s.find(by, from)) {
    parts.push_back(s.substr(from, at - from));
    from = at + 1;
  }
  parts.push_back(s.substr(from));
  return parts;
}

// The node the override `key` sets in the parsed scene, the way apply_override finds it; null
// when the scene does not hold the key (the loader then judges it).
const toml::node* find_key(const toml::table& root, const std::string& key) {
  const std::vector<std::string> parts = split(key, '.');
  if (parts.size() == 3 && parts[0] == "wall") {
    if (const auto* walls = root["wall"].as_array())
      for (const auto& w : *walls)
        if (const auto* t = w.as_table(); t && (*t)["name"].value<std::string>() == parts[1])
          return t->get(parts[2]);
    return nullptr;
  }
  if ((parts.size() == 3 || parts.size() == 4) && parts[0] == "body") {
    if (const auto* bodies = root["body"].as_array()) {
      std::size_t k = 0;
      for (const auto& b : *bodies) {
        const auto* t = b.as_table();
        if (!t || (*t)["name"].value_or(fmt::format("body{}", k++)) != parts[1]) continue;
        if (parts.size() == 3) return t->get(parts[2]);
        const auto* sub = (*t)[parts[2]].as_table();
        return sub ? sub->get(parts[3]) : nullptr;
      }
    }
    return nullptr;
  }
  if (parts.size() != 2) return nullptr;
  const auto* section = root[parts[0]].as_table();
  return section ? section->get(parts[1]) : nullptr;
}

std::optional<Vec3> as_vec3(const toml::node& n) {
  const auto* a = n.as_array();
  if (!a || a->size() != 3) return std::nullopt;
  Vec3 v;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto d = (*a)[k].value<double>();
    if (!d) return std::nullopt;
    v[static_cast<Eigen::Index>(k)] = *d;
  }
  return v;
}

// A key set from the command line has no line in the file: the loader's "file:0:0: " says nothing.
std::string without_position(const std::string& message, const std::filesystem::path& file) {
  const std::string empty_position = file.string() + ":0:0: ";
  const auto at = message.find(empty_position);
  if (at == std::string::npos) return message;
  return message.substr(0, at) + file.string() + ": " + message.substr(at + empty_position.size());
}

// The names a body. or wall. key can use, when the loader found none of that name.
std::string names_hint(const std::string& message, const Scene& scene) {
  std::string names;
  if (message.find("no [[body]] named") != std::string::npos) {
    for (const BodySpec& b : scene.bodies)
      if (!b.from_generator_section) names += fmt::format("{}{}", names.empty() ? "" : ", ", b.name);
    return names.empty() ? "; the scene has no [[body]] entries" : fmt::format("; the scene's [[body]] names: {}", names);
  }
  if (message.find("no [[wall]] named") != std::string::npos) {
    for (const Wall& w : scene.walls) names += fmt::format("{}{}", names.empty() ? "" : ", ", w.name);
    return names.empty() ? "; the scene has no [[wall]]" : fmt::format("; the scene's [[wall]] names: {}", names);
  }
  return {};
}

std::string vec_text(const Vec3& v) { return fmt::format("[{:g}, {:g}, {:g}]", v.x(), v.y(), v.z()); }

}  // namespace

VarySpec parse_vary(const std::string& text) {
  VarySpec spec;
  spec.text = text;
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw SceneError(fmt::format("--vary '{}': expected KEY=V1,V2,... (a scene key as --set takes it), e.g. "
                                 "--vary body.shard.velocity=1.0,1.5,2.0",
                                 text));
  std::string key = trimmed(text.substr(0, eq));
  if (key.empty())
    throw SceneError(fmt::format("--vary '{}': the key is missing before '=', e.g. body.shard.velocity=1.0,1.5", text));
  if (key.back() == ']') {
    const auto open = key.rfind('[');
    const std::string index = open == std::string::npos ? "" : key.substr(open + 1, key.size() - open - 2);
    if (index != "0" && index != "1" && index != "2")
      throw SceneError(fmt::format("--vary '{}': a vector component is written KEY[0], KEY[1] or KEY[2] (x, y, z)",
                                   text));
    spec.component = index[0] - '0';
    key = key.substr(0, open);
  }
  spec.key = key;
  const std::string list = text.substr(eq + 1);
  if (trimmed(list).empty())
    throw SceneError(fmt::format("--vary '{}': no values; give a comma-separated list, e.g. {}=1.0,1.5,2.0", text,
                                 text.substr(0, eq)));
  std::set<double> seen;
  for (const std::string& raw : split(list, ',')) {
    const std::string item = trimmed(raw);
    if (item.empty())
      throw SceneError(fmt::format("--vary '{}': an empty value in the list (two commas, or one at an end)", text));
    double v = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (ec != std::errc{} || end != item.data() + item.size() || !std::isfinite(v))
      throw SceneError(fmt::format("--vary '{}': '{}' is not a number; the values are numbers in SI units, e.g. "
                                   "1.5 or 2e-3",
                                   text, item));
    if (!seen.insert(v).second)
      throw SceneError(fmt::format("--vary '{}': the value {} is given twice; list each value once (--seeds "
                                   "repeats runs)",
                                   text, item));
    spec.values.push_back(v);
  }
  return spec;
}

SweepPlan plan_sweep(const std::filesystem::path& scene_file, const SceneOverrides& base, const VarySpec& vary,
                     const PluginHost& host) {
  SweepPlan plan;
  plan.vary = vary;
  const Scene scene = load_scene(scene_file, host, base);
  plan.scene_seed = scene.seed;
  for (const BodySpec& b : scene.bodies)
    if (b.stream && !b.from_generator_section) plan.stream_seeds.emplace_back(b.name, b.stream->seed);

  const toml::table root = toml::parse(scene.resolved_text);
  const toml::node* node = find_key(root, vary.key);
  const std::optional<Vec3> vector = node ? as_vec3(*node) : std::nullopt;
  if (vary.component) {
    if (!vector)
      throw SceneError(fmt::format("--vary '{}': {}[{}] sets a component of a vector, but the scene holds {} at {}; "
                                   "give the key without [{}]",
                                   vary.text, vary.key, *vary.component, node ? "no 3-vector" : "nothing", vary.key,
                                   *vary.component));
    plan.form = VaryForm::component;
    plan.base = *vector;
    plan.value_name = plan.value_label = fmt::format("{}[{}]", vary.key, *vary.component);
  } else if (vector) {
    if (!(vector->norm() > 0))
      throw SceneError(fmt::format("--vary '{}': the scene's {} is {}, which has no direction for a magnitude; vary "
                                   "a component instead, e.g. {}[2]=...",
                                   vary.text, vary.key, vec_text(*vector), vary.key));
    plan.form = VaryForm::magnitude;
    plan.base = *vector;
    plan.value_name = fmt::format("|{}|", vary.key);
    plan.value_label = fmt::format("|{}| along {}", vary.key, vec_text(vector->normalized()));
    for (double v : vary.values)
      if (v < 0)
        throw SceneError(fmt::format("--vary '{}': {} is a magnitude of the vector {} (direction kept) and cannot be "
                                     "negative; to reverse it, vary a component ({}[i])",
                                     vary.text, v, vary.key, vary.key));
  } else if (node && node->is_integer()) {
    plan.form = VaryForm::integer;
    plan.value_name = plan.value_label = vary.key;
    for (double v : vary.values)
      if (v != std::floor(v) || std::abs(v) > 9.0e15)
        throw SceneError(fmt::format("--vary '{}': {} takes whole numbers (the scene has {}), not {}", vary.text,
                                     vary.key, node->value<std::int64_t>().value_or(0), v));
  } else {
    plan.form = VaryForm::number;
    plan.value_name = plan.value_label = vary.key;
  }
  // Every value through the loader: an unknown key or a value out of range is refused now.
  for (double v : vary.values) {
    try {
      load_scene(scene_file, host, run_overrides(plan, base, v, 0));
    } catch (const SceneError& e) {
      throw SceneError(fmt::format("--vary '{}' (value {}): {}{}", vary.text, v, without_position(e.what(), scene_file),
                                   names_hint(e.what(), scene)));
    }
  }
  return plan;
}

SceneOverrides run_overrides(const SweepPlan& plan, const SceneOverrides& base, double value, std::int64_t seed) {
  SceneOverrides o = base;
  if (seed != 0) {
    o.push_back({"simulation.seed", static_cast<std::int64_t>(plan.scene_seed) + seed});
    for (const auto& [name, stream_seed] : plan.stream_seeds)
      o.push_back({fmt::format("body.{}.stream.seed", name), static_cast<std::int64_t>(stream_seed) + seed});
  }
  switch (plan.form) {
    case VaryForm::number:
      o.push_back({plan.vary.key, value});
      break;
    case VaryForm::integer:
      o.push_back({plan.vary.key, static_cast<std::int64_t>(value)});
      break;
    case VaryForm::magnitude:
      o.push_back({plan.vary.key, Vec3(value * plan.base.normalized())});
      break;
    case VaryForm::component: {
      Vec3 v = plan.base;
      v[*plan.vary.component] = value;
      o.push_back({plan.vary.key, v});
      break;
    }
  }
  return o;
}

}  // namespace shard
