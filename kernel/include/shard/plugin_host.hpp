#pragma once
// Finds, loads and keeps plugin shared objects; turns (kind, name, parameters) into models.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "shard/plugin.hpp"

namespace shard {

struct LoadedPlugin {
  // A bond law's params are its own followed by those of the bond effects loaded for it
  // (own_params holds its own); an effect's are its own.
  PluginInfo info;
  std::string file;  // the shared object it came from
  ContactFactory make_contact;
  BondFactory make_bond;
  GeneratorFactory make_generator;
  BondEffectFactory make_bond_effect;
  std::string law;                    // a bond effect: the bond law it composes onto
  std::vector<ParamSpec> own_params;  // a bond law: its schema without the effects'
};

// A parameter value as written in a scene, before validation (line/column for messages).
struct RawParam {
  ParamValue value;
  std::string where;  // "scene.toml:12:3"
};

class PluginError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class PluginHost {
 public:
  PluginHost();
  ~PluginHost();
  PluginHost(const PluginHost&) = delete;
  PluginHost& operator=(const PluginHost&) = delete;

  // Search path in priority order: explicit dirs, $SHARD_PLUGIN_PATH, build tree, install tree.
  static std::vector<std::filesystem::path> default_search_path(
      const std::vector<std::filesystem::path>& explicit_dirs = {});
  // Loads every shard_*.so in the folders; returns messages for files that were refused.
  std::vector<std::string> load_directories(const std::vector<std::filesystem::path>& dirs);
  // Loads one file; throws PluginError on an ABI mismatch or a refused bond effect (plugin_host.cpp).
  void load_file(const std::filesystem::path& file);

  const LoadedPlugin& find(PluginKind kind, const std::string& name) const;  // throws, listing names
  std::vector<const LoadedPlugin*> plugins() const;

  // Fills defaults, rejects unknown names, wrong types and out-of-range values.
  static ParamSet validate(const PluginInfo& info, const std::map<std::string, RawParam>& raw,
                           const std::string& section_where);

  std::unique_ptr<ContactModel> make_contact(const std::string& name, const ParamSet& p) const;
  // The law, with the bond effects loaded for it composed on (bond_effect.hpp) when the scene
  // names one in `effects` or sets a parameter of one away from its neutral value.
  std::unique_ptr<BondModel> make_bond(const std::string& name, const ParamSet& p) const;
  // The loaded bond effects that compose onto `law`, in name order.
  std::vector<const LoadedPlugin*> bond_effects_for(const std::string& law) const;
  // Those of them make_bond composes for these parameters (a run records their versions).
  std::vector<const LoadedPlugin*> bond_effects_on(const std::string& law, const ParamSet& p) const;
  std::unique_ptr<Generator> make_generator(const std::string& name, const ParamSet& p) const;
  // Convenience for tests and tools: validate plain values, then make.
  ParamSet params(PluginKind kind, const std::string& name,
                  const std::map<std::string, ParamValue>& values) const;

 private:
  struct Library;
  // Rebuilds each bond law's schema from its own and its effects' (after every load).
  void compose_effect_schemas();
  std::vector<std::unique_ptr<Library>> libraries_;  // declared first: destroyed last
  std::map<std::pair<int, std::string>, LoadedPlugin> plugins_;
};

// Closest candidate by edit distance, for "did you mean" hints; empty if none is close.
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace shard
