#include "material_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>

#include "scene_section.hpp"

namespace shard::scene_detail {
namespace {

const char* scope_section(ParamScope scope) {
  switch (scope) {
    case ParamScope::Material: return "[[material]]";
    case ParamScope::Pair: return "[[material_pair]]";
    case ParamScope::Model: break;
  }
  return "[contact]";
}

// An effect's parameter whose default is its neutral value: leaving it out keeps the effect off.
bool off_by_default(const ParamSpec& spec) {
  const double* value = std::get_if<double>(&spec.default_value);
  return value && spec.neutral && *value == *spec.neutral;
}

std::vector<const ParamSpec*> specs_of(const LoadedPlugin* law, ParamScope scope) {
  std::vector<const ParamSpec*> out;
  if (law)
    for (const auto& spec : law->info.params)
      if (spec.scope == scope) out.push_back(&spec);
  return out;
}

// The law's parameters of `scope` written in one entry (`raw`, the entry's keys left after its own),
// validated against the law's schema; `all`: every one of them is required.
ParamSet scoped_params(const std::map<std::string, RawParam>& raw, const LoadedPlugin* law, ParamScope scope,
                       bool all, const std::string& entry_where, const std::string& entry,
                       std::vector<std::string> own_keys) {
  const std::string section = scope == ParamScope::Material ? "material" : "material_pair";
  std::vector<std::string> valid = std::move(own_keys);
  for (const ParamSpec* spec : specs_of(law, scope)) valid.push_back(spec->name);
  for (const auto& [key, value] : raw) {
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    // A parameter of the law that belongs elsewhere gets the place it belongs.
    if (law)
      for (const auto& spec : law->info.params)
        if (spec.name == key)
          throw SceneError(fmt::format("{}: [{}] {} is given {} for {} (docs/reference/materials.md): move it to {}",
                                       value.where, section, key,
                                       spec.scope == ParamScope::Model ? "once" : (spec.scope == ParamScope::Pair
                                                                                       ? "per pair of materials"
                                                                                       : "per material"),
                                       law->info.name, scope_section(spec.scope)));
    const std::string hint = closest_match(key, valid);
    throw SceneError(fmt::format("{}: unknown key '{}' in [{}]{}; valid keys: {}{}", value.where, key, section,
                                 hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint), fmt::join(valid, ", "),
                                 law ? "" : " (the law's parameters need a [contact] section)"));
  }
  PluginInfo info;
  info.kind = PluginKind::Contact;
  info.name = law ? law->info.name : std::string();
  std::map<std::string, RawParam> given;
  for (const ParamSpec* spec : specs_of(law, scope)) {
    const auto it = raw.find(spec->name);
    if (it == raw.end()) {
      if (all)
        throw SceneError(fmt::format("{}: {} has no {} [{}], which {} takes per material ({}); add {} = ...",
                                     entry_where, entry, spec->name, spec->unit, info.name, spec->doc, spec->name));
      continue;
    }
    info.params.push_back(*spec);
    given.insert(*it);
  }
  try {
    return PluginHost::validate(info, given, entry_where);
  } catch (const PluginError& e) {
    throw SceneError(e.what());
  }
}

struct PairRow {
  ParamSet values;
  std::string where;
};

std::string listed(const std::vector<Material>& materials) {
  std::string s;
  for (const auto& m : materials) s += (s.empty() ? "'" : ", '") + m.name + "'";
  return s;
}

// The index of material `name` named at `where` by `user`; unnamed: the only material, or an
// error when there are several.
std::int32_t material_index(const std::vector<Material>& materials, const std::string& name, const std::string& where,
                            const std::string& user, bool table) {
  if (name.empty()) {
    if (materials.size() == 1) return 0;
    throw SceneError(fmt::format("{}: {} names no material, and the scene has {} ({}); add material = \"{}\" (or the "
                                 "one it is made of)",
                                 where, user, materials.size(), listed(materials), materials.front().name));
  }
  for (std::size_t k = 0; k < materials.size(); ++k)
    if (materials[k].name == name) return static_cast<std::int32_t>(k);
  std::vector<std::string> names;
  for (const auto& m : materials) names.push_back(m.name);
  const std::string hint = closest_match(name, names);
  throw SceneError(fmt::format("{}: {} names material '{}', which is no {}{}; the scene's materials: {}{}", where, user,
                               name, table ? "[[material]]" : "[material]",
                               hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint), listed(materials),
                               table ? "" : " (name the one [material] with name = \"...\", or write [[material]] "
                                            "entries)"));
}

// Why a pair of materials is needed: the first body and body, or body and wall, that can meet.
struct Need {
  std::string where, what;
};

// A scene of one [material] section: density and name; the contact law's parameters all in
// [contact]. Bodies and walls may still name that one material, and must name it right.
void read_single_material(const toml::table& root, const std::string& file, const toml::node* node,
                          const std::vector<WallMaterial>& walls, Scene& scene) {
  Section mat(node ? node->as_table() : nullptr, file, "material");
  scene.density = mat.number("density", 0, 0, 1e6, "kg/m^3");
  if (scene.density <= 0) mat.fail("density", "is missing: particle density in kg/m^3 (filter cake: 3720)");
  const std::string name = mat.text("name", "");
  mat.finish();
  if (root.contains("material_pair"))
    throw SceneError(fmt::format("{}: [[material_pair]] rows need [[material]] entries (a scene of one [material] "
                                 "takes every contact parameter from [contact]); write the materials as "
                                 "[[material]] (docs/reference/materials.md)",
                                 where(file, root.get("material_pair")->source())));
  scene.materials = {Material{name, mat.at(), scene.density, {}}};
  for (auto& body : scene.bodies)
    if (!body.material_name.empty())
      material_index(scene.materials, body.material_name, body.material_where, fmt::format("[[body]] '{}'", body.name),
                     false);
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (!walls[w].name.empty())
      material_index(scene.materials, walls[w].name, walls[w].where, fmt::format("[[wall]] '{}'", scene.walls[w].name),
                     false);
}

// Per-material and per-pair parameters live in [[material]] and [[material_pair]], never in [contact].
void refuse_material_params_in_contact(const toml::table& root, const std::string& file, const LoadedPlugin* law) {
  const auto* contact = root["contact"].as_table();
  if (!contact) return;
  for (const ParamScope scope : {ParamScope::Material, ParamScope::Pair})
    for (const ParamSpec* spec : specs_of(law, scope))
      if (const toml::node* given = contact->get(spec->name))
        throw SceneError(fmt::format("{}: [contact] {} is given {} in a scene with [[material]] entries "
                                     "(docs/reference/materials.md): move it to {}",
                                     where(file, given->source()), spec->name,
                                     scope == ParamScope::Pair ? "per pair of materials" : "per material",
                                     scope_section(scope)));
}

// The [[material]] entries, in order, each with a unique name and the law's per-material parameters.
void read_material_entries(const toml::array& array, const std::string& file, const LoadedPlugin* law, Scene& scene) {
  for (const auto& entry : array) {
    Section s(entry.as_table(), file, "material");
    Material m;
    m.where = s.at();
    m.name = s.text("name", "");
    if (m.name.empty() || m.name == "*" || m.name.find('/') != std::string::npos)
      s.fail("name", fmt::format("= '{}' cannot name a material: every [[material]] needs a name, not '*' and "
                                 "without '/', e.g. name = \"steel\"",
                                 m.name));
    for (const auto& earlier : scene.materials)
      if (earlier.name == m.name)
        s.fail("name", fmt::format("'{}' is used by two materials (the first at {}); give each [[material]] its own "
                                   "name",
                                   m.name, earlier.where));
    m.density = s.number("density", 0, 0, 1e6, "kg/m^3");
    if (entry.as_table()->contains("density") && !(m.density > 0))
      s.fail("density", "must be positive, in kg/m^3 (leave it out for a material only walls are made of)");
    std::map<std::string, RawParam> raw;
    s.finish(&raw);
    m.law = scoped_params(raw, law, ParamScope::Material, true, m.where, fmt::format("[[material]] '{}'", m.name),
                          {"name", "density"});
    scene.materials.push_back(std::move(m));
  }
}

// The [[material_pair]] rows: `rows` indexed a * count + b (both orders filled), `fallback` the
// default row ["*", "*"].
struct PairRows {
  std::vector<std::optional<PairRow>> rows;
  std::optional<PairRow> fallback;
};

// Reads one [[material_pair]] entry into its slot of `out`.
void read_pair_row(const toml::node& entry, const std::string& file, const LoadedPlugin* law,
                   const std::vector<Material>& materials, PairRows& out) {
  const std::size_t count = materials.size();
  Section s(entry.as_table(), file, "material_pair");
  const std::vector<std::string> names = s.strings("materials");
  if (names.size() != 2)
    s.fail("materials", "must name two materials, e.g. materials = [\"cake\", \"steel\"], or be [\"*\", \"*\"] "
                        "for the default of every pair without a row");
  const bool star0 = names[0] == "*", star1 = names[1] == "*";
  if (star0 != star1)
    s.fail("materials", "mixes a name and '*'; name two materials, or write [\"*\", \"*\"] for the default row");
  std::int32_t a = 0, b = 0;
  if (!star0) {
    a = material_index(materials, names[0], s.at("materials"), "[[material_pair]]", true);
    b = material_index(materials, names[1], s.at("materials"), "[[material_pair]]", true);
  }
  std::map<std::string, RawParam> raw;
  s.finish(&raw);
  PairRow row{scoped_params(raw, law, ParamScope::Pair, false, s.at(),
                            star0 ? std::string("[[material_pair]] [\"*\", \"*\"]")
                                  : fmt::format("[[material_pair]] ['{}', '{}']", names[0], names[1]),
                            {"materials"}),
              s.at()};
  std::optional<PairRow>& slot =
      star0 ? out.fallback : out.rows[static_cast<std::size_t>(a) * count + static_cast<std::size_t>(b)];
  if (slot)
    s.fail("materials",
           fmt::format("repeats the pair of the row at {}; give each pair one [[material_pair]]", slot->where));
  slot = row;
  if (!star0) out.rows[static_cast<std::size_t>(b) * count + static_cast<std::size_t>(a)] = row;
}

// Pair rows: two names, or the default row ["*", "*"].
PairRows read_pair_rows(const toml::table& root, const std::string& file, const LoadedPlugin* law,
                        const std::vector<Material>& materials) {
  PairRows out;
  out.rows.resize(materials.size() * materials.size());
  const toml::node* pairs = root.get("material_pair");
  if (!pairs) return out;
  const auto* list = pairs->as_array();
  if (!list || !list->is_array_of_tables())
    throw SceneError(fmt::format("{}: material pairs are an array of tables: write [[material_pair]]",
                                 where(file, pairs->source())));
  for (const auto& entry : *list) read_pair_row(entry, file, law, materials, out);
  return out;
}

// Every body's material index; a body's material must have a density.
void assign_body_materials(Scene& scene) {
  for (auto& body : scene.bodies) {
    const std::string user = body.from_generator_section ? "[generator]" : fmt::format("[[body]] '{}'", body.name);
    // The single [generator] body is of the first material (it has no key to name one).
    body.material = body.from_generator_section
                        ? 0
                        : material_index(scene.materials, body.material_name, body.material_where, user, true);
    const Material& m = scene.materials[static_cast<std::size_t>(body.material)];
    if (!(m.density > 0))
      throw SceneError(fmt::format("{}: {} is of material '{}', which has no density; add density = ... [kg/m^3] to "
                                   "its [[material]] at {}",
                                   body.material_where, user, m.name, m.where));
  }
}

// Why each pair of materials is needed (indexed a * count + b, both orders), the first reason found.
using PairNeeds = std::vector<std::optional<Need>>;

// Every wall's material index; the pairs that can meet: two bodies' (a body's pieces meet each
// other too) and a body's and a wall's.
PairNeeds pairs_that_meet(const std::vector<WallMaterial>& walls, Scene& scene) {
  const std::size_t count = scene.materials.size();
  PairNeeds needs(count * count);
  const auto need = [&](std::int32_t a, std::int32_t b, const Need& why) {
    for (const std::size_t k : {static_cast<std::size_t>(a) * count + static_cast<std::size_t>(b),
                                static_cast<std::size_t>(b) * count + static_cast<std::size_t>(a)})
      if (!needs[k]) needs[k] = why;
  };
  const auto material_name = [&](std::int32_t k) -> const std::string& {
    return scene.materials[static_cast<std::size_t>(k)].name;
  };
  for (std::size_t x = 0; x < scene.bodies.size(); ++x)
    for (std::size_t y = x; y < scene.bodies.size(); ++y) {
      const BodySpec &p = scene.bodies[x], &q = scene.bodies[y];
      need(p.material, q.material,
           {p.material_where, x == y ? fmt::format("the pieces of body '{}' of '{}'", p.name, material_name(p.material))
                                     : fmt::format("body '{}' of '{}' can touch body '{}' of '{}'", p.name,
                                                   material_name(p.material), q.name, material_name(q.material))});
    }
  for (std::size_t w = 0; w < scene.walls.size(); ++w) {
    Wall& wall = scene.walls[w];
    wall.material = material_index(scene.materials, walls[w].name, walls[w].where,
                                   fmt::format("[[wall]] '{}'", wall.name), true);
    for (const auto& body : scene.bodies)
      need(body.material, wall.material,
           {walls[w].where, fmt::format("body '{}' of '{}' can touch wall '{}' of '{}'", body.name,
                                        material_name(body.material), wall.name, material_name(wall.material))});
  }
  return needs;
}

// Each pair's parameters: its row, else the default row; a pair that can meet must have them
// all, except an effect's parameter whose default is its neutral value (e.g. rolling_friction
// 0): given by no row, the effect stays off for that pair. A pair that cannot meet keeps the
// law's defaults (never read).
void fill_pair_params(const PairRows& pair_rows, const PairNeeds& needs, const LoadedPlugin* law, Scene& scene) {
  const std::size_t count = scene.materials.size();
  const auto& rows = pair_rows.rows;
  const auto& fallback = pair_rows.fallback;
  scene.material_pairs.assign(count * count, ParamSet{});
  for (std::size_t a = 0; a < count; ++a)
    for (std::size_t b = 0; b < count; ++b) {
      const std::size_t k = a * count + b;
      for (const ParamSpec* spec : specs_of(law, ParamScope::Pair)) {
        if (rows[k] && rows[k]->values.has(spec->name)) {
          scene.material_pairs[k].set(spec->name, rows[k]->values.all().at(spec->name));
        } else if (fallback && fallback->values.has(spec->name)) {
          scene.material_pairs[k].set(spec->name, fallback->values.all().at(spec->name));
        } else if (needs[k] && !off_by_default(*spec)) {
          const std::string &na = scene.materials[a].name, &nb = scene.materials[b].name;
          throw SceneError(fmt::format(
              "{}: no [[material_pair]] gives {} [{}] for materials '{}' and '{}', which meet ({}); add a row "
              "[[material_pair]] materials = [\"{}\", \"{}\"] with {} = ..., or a default row materials = "
              "[\"*\", \"*\"] (docs/reference/materials.md)",
              needs[k]->where, spec->name, spec->unit, na, nb, needs[k]->what, na, nb, spec->name));
        } else {
          std::visit(
              [&](const auto& d) {
                if constexpr (!std::is_same_v<std::decay_t<decltype(d)>, std::monostate>)
                  scene.material_pairs[k].set(spec->name, d);
              },
              spec->default_value);
        }
      }
    }
}

}  // namespace

void check_material_overrides(const SceneOverrides& overrides, const PluginHost& host, const Scene& scene) {
  const LoadedPlugin* law = scene.contact ? &host.find(PluginKind::Contact, scene.contact->name) : nullptr;
  for (const SceneOverride& o : overrides) {
    const bool material = o.key.rfind("material.", 0) == 0 && std::count(o.key.begin(), o.key.end(), '.') == 2;
    const bool pair = o.key.rfind("material_pair.", 0) == 0 && std::count(o.key.begin(), o.key.end(), '.') == 3;
    if (!material && !pair) continue;
    const std::string key = o.key.substr(o.key.rfind('.') + 1);
    const ParamScope scope = material ? ParamScope::Material : ParamScope::Pair;
    std::vector<std::string> valid;
    if (material) valid.push_back("density");
    for (const ParamSpec* spec : specs_of(law, scope)) valid.push_back(spec->name);
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    std::string names = o.key.substr(o.key.find('.') + 1, o.key.rfind('.') - o.key.find('.') - 1);
    if (pair) names = fmt::format("['{}']", names.replace(names.find('.'), 1, "', '"));
    else names = fmt::format("'{}'", names);
    if (law)
      for (const auto& spec : law->info.params)
        if (spec.name == key) {
          const std::string form = spec.scope == ParamScope::Model
                                       ? fmt::format("contact.{}", key)
                                       : (spec.scope == ParamScope::Pair ? fmt::format("material_pair.A.B.{}", key)
                                                                         : fmt::format("material.NAME.{}", key));
          throw SceneError(fmt::format("--set '{}': {} takes {} {} (docs/reference/materials.md): set it with --set {}=...",
                                       o.text(), law->info.name, key,
                                       spec.scope == ParamScope::Model
                                           ? "once, in [contact]"
                                           : (spec.scope == ParamScope::Pair ? "per pair of materials"
                                                                             : "per material"),
                                       form));
        }
    std::string hint = closest_match(key, valid);
    if (hint.empty() && law) {
      // A misspelt parameter of the other table: name it with the override that reaches it.
      std::vector<std::string> others;
      for (const auto& spec : law->info.params) others.push_back(spec.name);
      const std::string other = closest_match(key, others);
      for (const auto& spec : law->info.params)
        if (!other.empty() && spec.name == other)
          hint = spec.scope == ParamScope::Pair    ? fmt::format("material_pair.A.B.{}", other)
                 : spec.scope == ParamScope::Model ? fmt::format("contact.{}", other)
                                                   : fmt::format("material.NAME.{}", other);
    }
    throw SceneError(fmt::format("--set '{}': unknown key '{}' for {} {}{}; valid keys: {}", o.text(), key,
                                 material ? "[[material]]" : "[[material_pair]]", names,
                                 hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                                 valid.empty() ? std::string("none (the scene has no [contact] law)")
                                               : fmt::format("{}", fmt::join(valid, ", "))));
  }
}

void read_materials(const toml::table& root, const std::string& file, const PluginHost& host,
                    const std::vector<WallMaterial>& walls, Scene& scene) {
  const toml::node* node = root.get("material");
  if (!node || node->as_table()) {
    read_single_material(root, file, node, walls, scene);
    return;
  }
  const auto* array = node->as_array();
  if (!array || !array->is_array_of_tables())
    throw SceneError(fmt::format("{}: material must be one [material] section or [[material]] entries",
                                 where(file, node->source())));
  scene.material_table = true;
  const LoadedPlugin* law = scene.contact ? &host.find(PluginKind::Contact, scene.contact->name) : nullptr;
  refuse_material_params_in_contact(root, file, law);
  read_material_entries(*array, file, law, scene);
  scene.density = scene.materials.front().density;
  const PairRows rows = read_pair_rows(root, file, law, scene.materials);
  assign_body_materials(scene);
  const PairNeeds needs = pairs_that_meet(walls, scene);
  fill_pair_params(rows, needs, law, scene);
}

}  // namespace shard::scene_detail
