#pragma once
// The plugin ABI. Every plugin shared object defines two C symbols with SHARD_PLUGIN:
//   int  shard_plugin_abi(void)            -> the kAbiVersion it was compiled with
//   void shard_plugin_register(Registrar*) -> registers its models (and bond effects)
// The host reads the first before calling the second, so a plugin built against other headers
// is refused with a message instead of crashing on a changed class layout.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "shard/bond_effect.hpp"
#include "shard/bond_model.hpp"
#include "shard/contact_model.hpp"
#include "shard/generator.hpp"
#include "shard/params.hpp"

namespace shard {

// Bump on any change to a header plugins compile against (the installed API, docs/how-to/write-a-plugin.md).
// 2: BondModel::writes_every_output; 3: bond effects (bond_effect.hpp, Registrar::add_bond_effect)
// and the installed API reduced to the plugin headers; 4: materials (ParamSpec::scope,
// ContactBatch::material_pair, ContactModel::set_materials and its per-material time step);
// 5: ParticleView::flags and kUnbreakable (a bond model keeps the bonds of unbreakable zones).
inline constexpr int kAbiVersion = 5;

enum class PluginKind { Contact, Bond, Generator, BondEffect };
const char* to_string(PluginKind kind);

struct PluginInfo {
  PluginKind kind;
  std::string name;     // scene name, e.g. "hertz_mindlin"
  std::string version;  // the model's own version, stored in every output
  std::string doc;      // one line
  std::vector<ParamSpec> params;
};

using ContactFactory = std::function<std::unique_ptr<ContactModel>(const ParamSet&)>;
using BondFactory = std::function<std::unique_ptr<BondModel>(const ParamSet&)>;
using GeneratorFactory = std::function<std::unique_ptr<Generator>(const ParamSet&)>;

class Registrar {
 public:
  virtual ~Registrar() = default;
  virtual void add_contact(PluginInfo info, ContactFactory make) = 0;
  virtual void add_bond(PluginInfo info, BondFactory make) = 0;
  virtual void add_generator(PluginInfo info, GeneratorFactory make) = 0;
  // An effect composed onto the bond law named `law` (bond_effect.hpp). Its parameters join the
  // law's [bond] table, so their names must differ from the law's (prefix them with the effect's).
  virtual void add_bond_effect(PluginInfo info, std::string law, BondEffectFactory make) = 0;
};

}  // namespace shard

#define SHARD_PLUGIN(registrar_param)                                                \
  extern "C" __attribute__((visibility("default"))) int shard_plugin_abi() {          \
    return ::shard::kAbiVersion;                                                      \
  }                                                                                   \
  extern "C" __attribute__((visibility("default"))) void shard_plugin_register(      \
      ::shard::Registrar* registrar_param)
