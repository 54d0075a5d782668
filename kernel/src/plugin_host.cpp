#include "shard/plugin_host.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <sstream>

#include "composed_bond.hpp"
#include "shard/install_layout.hpp"

namespace shard {

const char* to_string(PluginKind kind) {
  switch (kind) {
    case PluginKind::Contact: return "contact";
    case PluginKind::Bond: return "bond";
    case PluginKind::Generator: return "generator";
    case PluginKind::BondEffect: return "bond_effect";
  }
  return "?";
}

struct PluginHost::Library {
  void* handle = nullptr;
  explicit Library(void* h) : handle(h) {}
  ~Library() {
    if (handle) dlclose(handle);
  }
  Library(const Library&) = delete;
  Library& operator=(const Library&) = delete;
};

namespace {

class HostRegistrar final : public Registrar {
 public:
  HostRegistrar(std::string file, std::vector<LoadedPlugin>& out) : file_(std::move(file)), out_(out) {}
  void add_contact(PluginInfo info, ContactFactory make) override {
    info.kind = PluginKind::Contact;
    added(std::move(info)).make_contact = std::move(make);
  }
  void add_bond(PluginInfo info, BondFactory make) override {
    info.kind = PluginKind::Bond;
    LoadedPlugin& p = added(std::move(info));
    p.own_params = p.info.params;
    p.make_bond = std::move(make);
  }
  void add_generator(PluginInfo info, GeneratorFactory make) override {
    info.kind = PluginKind::Generator;
    added(std::move(info)).make_generator = std::move(make);
  }
  void add_bond_effect(PluginInfo info, std::string law, BondEffectFactory make) override {
    info.kind = PluginKind::BondEffect;
    LoadedPlugin& p = added(std::move(info));
    p.law = std::move(law);
    p.make_bond_effect = std::move(make);
  }

 private:
  LoadedPlugin& added(PluginInfo info) {
    LoadedPlugin& p = out_.emplace_back();
    p.info = std::move(info);
    p.file = file_;
    return p;
  }
  std::string file_;
  std::vector<LoadedPlugin>& out_;
};

// Plugins that were retired, each with the scene line that replaces it: the one table of such
// hints (a scene naming a retired plugin gets its row instead of a bare "unknown plugin").
struct RetiredPlugin {
  PluginKind kind;
  const char* name;
  const char* replacement;
};
constexpr RetiredPlugin kRetiredPlugins[] = {
    {PluginKind::Contact, "hertz_mindlin_plus",
     "plugin = \"hertz_mindlin\" with effects = \"cohesion, support_friction\" (or just their parameters), "
     "cohesion_stress unchanged, and wall_friction = mu_w as support_friction_ratio = mu_w / friction "
     "(docs/reference/effects.md)"},
    {PluginKind::Bond, "beam_bond_plus",
     "plugin = \"beam_bond\" with effects = \"weibull_strength, softening, viscosity, compression_asymmetry\" "
     "(name the ones you use; their parameters keep their names, docs/reference/effects.md)"},
};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// True when the scene moved a parameter of `spec` away from its neutral value.
bool away_from_neutral(const ParamSpec& spec, const ParamSet& p) {
  if (!spec.neutral || !p.has(spec.name)) return false;
  const ParamValue& v = p.all().at(spec.name);
  if (const auto* d = std::get_if<double>(&v)) return *d != *spec.neutral;
  if (const auto* b = std::get_if<bool>(&v)) return (*b ? 1.0 : 0.0) != *spec.neutral;
  return false;
}

// The first parameter name `effect` shares with `params`, or "".
std::string shared_name(const std::vector<ParamSpec>& params, const PluginInfo& effect) {
  for (const auto& e : effect.params)
    for (const auto& q : params)
      if (q.name == e.name) return e.name;
  return "";
}

std::string type_name(ParamType t) {
  switch (t) {
    case ParamType::Number: return "a number";
    case ParamType::Integer: return "an integer";
    case ParamType::Boolean: return "true or false";
    case ParamType::String: return "a string";
    case ParamType::Vector3: return "an array of three numbers";
  }
  return "?";
}

}  // namespace

PluginHost::PluginHost() = default;
PluginHost::~PluginHost() {
  // Factories hold code from the libraries: drop them before the libraries close.
  plugins_.clear();
}

std::vector<std::filesystem::path> PluginHost::default_search_path(
    const std::vector<std::filesystem::path>& explicit_dirs) {
  std::vector<std::filesystem::path> dirs = explicit_dirs;
  if (const char* env = std::getenv("SHARD_PLUGIN_PATH")) {
    std::stringstream ss(env);
    std::string part;
    while (std::getline(ss, part, ':'))
      if (!part.empty()) dirs.emplace_back(part);
  }
  // The shipped plugins: the build tree's folder, or the installed one beside the library.
  dirs.push_back(install_layout().plugin_dir);
  return dirs;
}

std::vector<std::string> PluginHost::load_directories(const std::vector<std::filesystem::path>& dirs) {
  std::vector<std::string> refused;
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) continue;
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const auto name = entry.path().filename().string();
      if (name.rfind("shard_", 0) == 0 && entry.path().extension() == ".so") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());  // deterministic load order
    for (const auto& f : files) {
      try {
        load_file(f);
      } catch (const PluginError& e) {
        refused.emplace_back(e.what());
      }
    }
  }
  return refused;
}

void PluginHost::load_file(const std::filesystem::path& file) {
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw PluginError(fmt::format("{}: cannot load plugin: {}", file.string(), dlerror()));
  auto library = std::make_unique<Library>(handle);
  using AbiFn = int (*)();
  using RegisterFn = void (*)(Registrar*);
  auto abi = reinterpret_cast<AbiFn>(dlsym(handle, "shard_plugin_abi"));
  auto reg = reinterpret_cast<RegisterFn>(dlsym(handle, "shard_plugin_register"));
  if (!abi || !reg)
    throw PluginError(fmt::format(
        "{}: not a Shard plugin (missing shard_plugin_abi/shard_plugin_register; define them with SHARD_PLUGIN)",
        file.string()));
  const int plugin_abi = abi();
  if (plugin_abi != kAbiVersion)
    throw PluginError(fmt::format(
        "{}: plugin ABI version {} does not match this Shard's ABI version {}; rebuild the plugin "
        "against the installed Shard headers",
        file.string(), plugin_abi, kAbiVersion));
  std::vector<LoadedPlugin> found;
  HostRegistrar registrar(file.string(), found);
  try {
    reg(&registrar);
  } catch (const std::exception& e) {
    throw PluginError(fmt::format("{}: plugin failed while registering: {}", file.string(), e.what()));
  }
  // An effect's parameters join its law's [bond] table, so no name may be taken twice. Pairs of
  // plugins loaded before were checked then; a plugin shadowed by an earlier one takes no part.
  // A clash refuses the effect: this file when the effect is in it, else the effect loaded
  // before (a user's effect folder comes first on the search path), which is dropped while this
  // file's law loads, and the error names it.
  std::vector<const LoadedPlugin*> loaded, fresh;
  for (const auto& [key, q] : plugins_) loaded.push_back(&q);
  for (const auto& q : found)
    if (!plugins_.count({static_cast<int>(q.info.kind), q.info.name})) fresh.push_back(&q);
  std::vector<std::string> dropped;  // names of loaded effects refused, with the message
  std::string dropped_messages;
  for (const auto* p : fresh) {
    std::vector<const LoadedPlugin*> others = loaded;
    for (const auto* q : fresh)
      if (q != p) others.push_back(q);
    for (const auto* q : others) {
      const bool p_effect = p->info.kind == PluginKind::BondEffect, q_effect = q->info.kind == PluginKind::BondEffect;
      std::string name;
      if (p_effect && q->info.kind == PluginKind::Bond && q->info.name == p->law)
        name = shared_name(q->own_params, p->info);
      else if (q_effect && p->info.kind == PluginKind::Bond && p->info.name == q->law)
        name = shared_name(p->own_params, q->info);
      else if (p_effect && q_effect && p->law == q->law)
        name = shared_name(q->info.params, p->info);
      if (name.empty()) continue;
      const LoadedPlugin* effect = p_effect ? p : q;
      const std::string message = fmt::format(
          "{}: bond effect '{}' refused: its parameter '{}' is also declared by {} '{}' ({}), which shares the [bond] "
          "table of '{}'; prefix a bond effect's parameters with its name",
          effect->file, effect->info.name, name, to_string((p_effect ? q : p)->info.kind),
          (p_effect ? q : p)->info.name, (p_effect ? q : p)->file, effect->law);
      const bool effect_loaded_before = std::find(loaded.begin(), loaded.end(), effect) != loaded.end();
      if (!effect_loaded_before) throw PluginError(message);
      if (std::find(dropped.begin(), dropped.end(), effect->info.name) == dropped.end()) {
        dropped.push_back(effect->info.name);
        dropped_messages += (dropped_messages.empty() ? "" : "\n") + message;
      }
    }
  }
  for (const auto& name : dropped) plugins_.erase({static_cast<int>(PluginKind::BondEffect), name});
  for (auto& p : found) {
    const auto key = std::make_pair(static_cast<int>(p.info.kind), p.info.name);
    // The first directory on the search path wins, so a user's plugin shadows a built-in one.
    if (plugins_.count(key)) continue;
    plugins_.emplace(key, std::move(p));
  }
  libraries_.push_back(std::move(library));
  compose_effect_schemas();
  if (!dropped_messages.empty()) throw PluginError(dropped_messages);  // this file itself is loaded
}

void PluginHost::compose_effect_schemas() {
  for (auto& [key, law] : plugins_) {
    if (law.info.kind != PluginKind::Bond) continue;
    law.info.params = law.own_params;
    const auto effects = bond_effects_for(law.info.name);
    if (effects.empty()) continue;
    std::vector<std::string> names;
    for (const auto* e : effects) names.push_back(e->info.name);
    auto listed = std::find_if(law.info.params.begin(), law.info.params.end(),
                               [](const ParamSpec& s) { return s.name == "effects"; });
    if (listed == law.info.params.end()) {
      ParamSpec spec;
      spec.name = "effects";
      spec.type = ParamType::String;
      spec.default_value = std::string();
      law.info.params.push_back(spec);
      listed = std::prev(law.info.params.end());
      listed->doc = "effect policies composed onto the law, e.g. \"" + names.front() + "\"";
    }
    listed->doc += "; out-of-tree effects loaded: " + joined(names);
    for (const auto* e : effects)
      for (const auto& spec : e->info.params) law.info.params.push_back(spec);
  }
}

std::vector<const LoadedPlugin*> PluginHost::bond_effects_for(const std::string& law) const {
  std::vector<const LoadedPlugin*> out;
  for (const auto& [key, p] : plugins_)
    if (p.info.kind == PluginKind::BondEffect && p.law == law) out.push_back(&p);
  return out;
}

std::vector<const LoadedPlugin*> PluginHost::plugins() const {
  std::vector<const LoadedPlugin*> out;
  for (const auto& [key, p] : plugins_) out.push_back(&p);
  return out;
}

const LoadedPlugin& PluginHost::find(PluginKind kind, const std::string& name) const {
  auto it = plugins_.find({static_cast<int>(kind), name});
  if (it != plugins_.end()) return it->second;
  for (const auto& retired : kRetiredPlugins)
    if (retired.kind == kind && name == retired.name)
      throw PluginError(fmt::format("{} plugin '{}' was retired: write {}", to_string(kind), name,
                                    retired.replacement));
  std::vector<std::string> names;
  for (const auto& [key, p] : plugins_)
    if (key.first == static_cast<int>(kind)) names.push_back(p.info.name);
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  const std::string hint = closest_match(name, names);
  throw PluginError(fmt::format("unknown {} plugin '{}'{}; available: {}{}", to_string(kind), name,
                                hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                                list.empty() ? "none" : list,
                                list.empty() ? " (check --plugin-dir or SHARD_PLUGIN_PATH)" : ""));
}

ParamSet PluginHost::validate(const PluginInfo& info, const std::map<std::string, RawParam>& raw,
                              const std::string& section_where) {
  ParamSet out;
  std::vector<std::string> names;
  for (const auto& spec : info.params) names.push_back(spec.name);
  for (const auto& [name, value] : raw) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      const std::string hint = closest_match(name, names);
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      throw PluginError(fmt::format("{}: unknown parameter '{}' for {} plugin '{}'{}; valid: {}", value.where,
                                    name, to_string(info.kind), info.name,
                                    hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint), list));
    }
  }
  for (const auto& spec : info.params) {
    auto it = raw.find(spec.name);
    const std::string where = it != raw.end() ? it->second.where : section_where;
    ParamValue value;
    if (it == raw.end()) {
      if (std::holds_alternative<std::monostate>(spec.default_value))
        throw PluginError(fmt::format("{}: {} plugin '{}' needs parameter '{}' [{}]: {}", section_where,
                                      to_string(info.kind), info.name, spec.name, spec.unit, spec.doc));
      std::visit(
          [&](const auto& d) {
            if constexpr (!std::is_same_v<std::decay_t<decltype(d)>, std::monostate>) value = d;
          },
          spec.default_value);
    } else {
      value = it->second.value;
    }
    const auto wrong_type = [&] {
      return PluginError(fmt::format("{}: parameter '{}' of {} plugin '{}' must be {}", where, spec.name,
                                     to_string(info.kind), info.name, type_name(spec.type)));
    };
    switch (spec.type) {
      case ParamType::Number:
      case ParamType::Integer: {
        auto* d = std::get_if<double>(&value);
        if (!d) throw wrong_type();
        if (spec.type == ParamType::Integer && std::floor(*d) != *d) throw wrong_type();
        const bool below = spec.min_exclusive ? !(*d > spec.min) : !(*d >= spec.min);
        if (!std::isfinite(*d) || below || !(*d <= spec.max))
          throw PluginError(fmt::format("{}: parameter '{}' = {} [{}] of {} plugin '{}' is out of range {}{}, {}]; {}",
                                        where, spec.name, *d, spec.unit, to_string(info.kind), info.name,
                                        spec.min_exclusive ? "(" : "[", spec.min, spec.max, spec.doc));
        break;
      }
      case ParamType::Boolean:
        if (!std::holds_alternative<bool>(value)) throw wrong_type();
        break;
      case ParamType::String:
        if (!std::holds_alternative<std::string>(value)) throw wrong_type();
        break;
      case ParamType::Vector3:
        if (!std::holds_alternative<Vec3>(value)) throw wrong_type();
        break;
    }
    out.set(spec.name, value);
  }
  return out;
}

std::unique_ptr<ContactModel> PluginHost::make_contact(const std::string& name, const ParamSet& p) const {
  return find(PluginKind::Contact, name).make_contact(p);
}
std::unique_ptr<BondModel> PluginHost::make_bond(const std::string& name, const ParamSet& p) const {
  const LoadedPlugin& law = find(PluginKind::Bond, name);
  const auto effects = bond_effects_for(name);
  if (effects.empty()) return law.make_bond(p);

  // The law gets its own parameters, with `effects` stripped of the names it does not know.
  const bool law_lists_effects = std::any_of(law.own_params.begin(), law.own_params.end(),
                                             [](const ParamSpec& s) { return s.name == "effects"; });
  std::vector<std::string> named = p.names("effects");
  std::vector<std::string> law_named;
  for (const auto& n : named)
    if (std::none_of(effects.begin(), effects.end(), [&](const LoadedPlugin* e) { return e->info.name == n; }))
      law_named.push_back(n);
  if (!law_lists_effects && !law_named.empty()) {
    std::vector<std::string> valid;
    for (const auto* e : effects) valid.push_back(e->info.name);
    throw PluginError(fmt::format("bond plugin '{}': effects names '{}', which is no effect loaded for it; valid: {}",
                                  name, law_named.front(), joined(valid)));
  }
  ParamSet law_params;
  for (const auto& spec : law.own_params)
    if (p.has(spec.name)) law_params.set(spec.name, p.all().at(spec.name));
  if (law_lists_effects) law_params.set("effects", joined(law_named));

  std::vector<std::unique_ptr<BondEffect>> on;
  for (const auto* e : bond_effects_on(name, p)) {
    ParamSet own;
    for (const auto& spec : e->info.params)
      if (p.has(spec.name)) own.set(spec.name, p.all().at(spec.name));
    on.push_back(e->make_bond_effect(own));
  }
  // With every effect off the law runs alone, exactly as without the effect plugins.
  if (on.empty()) return law.make_bond(law_params);
  return std::make_unique<ComposedBond>(law.make_bond(law_params), std::move(on));
}
std::vector<const LoadedPlugin*> PluginHost::bond_effects_on(const std::string& law, const ParamSet& p) const {
  const std::vector<std::string> named = p.names("effects");
  std::vector<const LoadedPlugin*> on;
  for (const auto* e : bond_effects_for(law)) {
    const bool is_named = std::find(named.begin(), named.end(), e->info.name) != named.end();
    const bool moved = std::any_of(e->info.params.begin(), e->info.params.end(),
                                   [&](const ParamSpec& s) { return away_from_neutral(s, p); });
    if (is_named || moved) on.push_back(e);
  }
  return on;
}

std::unique_ptr<Generator> PluginHost::make_generator(const std::string& name, const ParamSet& p) const {
  return find(PluginKind::Generator, name).make_generator(p);
}

ParamSet PluginHost::params(PluginKind kind, const std::string& name,
                            const std::map<std::string, ParamValue>& values) const {
  std::map<std::string, RawParam> raw;
  for (const auto& [k, v] : values) raw[k] = RawParam{v, "<program>"};
  return validate(find(kind, name).info, raw, "<program>");
}

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    // Levenshtein distance, two rows.
    std::vector<std::size_t> prev(c.size() + 1), cur(c.size() + 1);
    for (std::size_t k = 0; k <= c.size(); ++k) prev[k] = k;
    for (std::size_t a = 1; a <= word.size(); ++a) {
      cur[0] = a;
      for (std::size_t b = 1; b <= c.size(); ++b)
        cur[b] = std::min({prev[b] + 1, cur[b - 1] + 1, prev[b - 1] + (word[a - 1] == c[b - 1] ? 0u : 1u)});
      std::swap(prev, cur);
    }
    if (prev[c.size()] < best_distance) {
      best_distance = prev[c.size()];
      best = c;
    }
  }
  return best;
}

}  // namespace shard
