#include "shard/plugin_host.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace shard {

const char* to_string(PluginKind kind) {
  switch (kind) {
    case PluginKind::Contact: return "contact";
    case PluginKind::Bond: return "bond";
    case PluginKind::Generator: return "generator";
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
    LoadedPlugin p{std::move(info), file_, std::move(make), {}, {}};
    out_.push_back(std::move(p));
  }
  void add_bond(PluginInfo info, BondFactory make) override {
    info.kind = PluginKind::Bond;
    LoadedPlugin p{std::move(info), file_, {}, std::move(make), {}};
    out_.push_back(std::move(p));
  }
  void add_generator(PluginInfo info, GeneratorFactory make) override {
    info.kind = PluginKind::Generator;
    LoadedPlugin p{std::move(info), file_, {}, {}, std::move(make)};
    out_.push_back(std::move(p));
  }

 private:
  std::string file_;
  std::vector<LoadedPlugin>& out_;
};

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
  dirs.emplace_back(SHARD_BUILD_PLUGIN_DIR);
  dirs.emplace_back(SHARD_INSTALL_PLUGIN_DIR);
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
  for (auto& p : found) {
    const auto key = std::make_pair(static_cast<int>(p.info.kind), p.info.name);
    // The first directory on the search path wins, so a user's plugin shadows a built-in one.
    if (plugins_.count(key)) continue;
    plugins_.emplace(key, std::move(p));
  }
  libraries_.push_back(std::move(library));
}

std::vector<const LoadedPlugin*> PluginHost::plugins() const {
  std::vector<const LoadedPlugin*> out;
  for (const auto& [key, p] : plugins_) out.push_back(&p);
  return out;
}

namespace {

// Plugins that became effect policies of another law: a scene naming one learns how to write it now.
std::string retired_plugin_hint(PluginKind kind, const std::string& name) {
  if (kind == PluginKind::Contact && name == "hertz_mindlin_plus")
    return "plugin = \"hertz_mindlin_plus\" names a removed plugin: its effects are policies of hertz_mindlin "
           "now. Write plugin = \"hertz_mindlin\" with effects = \"cohesion, support_friction\" (or just their "
           "parameters), cohesion_stress unchanged, and wall_friction = mu_w as support_friction_ratio = "
           "mu_w / friction (docs/effects.md)";
  if (kind == PluginKind::Bond && name == "beam_bond_plus")
    return "plugin = \"beam_bond_plus\" names a removed plugin: its effects are policies of beam_bond now. Write "
           "plugin = \"beam_bond\" with the same parameters, or name them in effects = \"...\" (docs/effects.md)";
  return "";
}

}  // namespace

const LoadedPlugin& PluginHost::find(PluginKind kind, const std::string& name) const {
  auto it = plugins_.find({static_cast<int>(kind), name});
  if (it != plugins_.end()) return it->second;
  if (const std::string hint = retired_plugin_hint(kind, name); !hint.empty()) throw PluginError(hint);
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
  return find(PluginKind::Bond, name).make_bond(p);
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
