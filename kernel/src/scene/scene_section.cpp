#include "scene_section.hpp"

namespace shard::scene_detail {

PluginChoice plugin_choice(const toml::table* table, const std::string& file, const std::string& name,
                           PluginKind kind, const PluginHost& host) {
  Section s(table, file, name);
  PluginChoice choice;
  choice.where = s.at();
  choice.name = s.text("plugin", "");
  if (choice.name.empty()) s.fail("plugin", "is missing: name the plugin, e.g. plugin = \"...\" (see `shard plugins`)");
  std::map<std::string, RawParam> raw;
  s.finish(&raw);
  const LoadedPlugin* plugin = nullptr;
  try {
    plugin = &host.find(kind, choice.name);
  } catch (const PluginError& e) {
    throw SceneError(fmt::format("{}: {}", s.at("plugin"), e.what()));
  }
  try {
    choice.params = PluginHost::validate(plugin->info, raw, choice.where);
  } catch (const PluginError& e) {
    throw SceneError(e.what());
  }
  return choice;
}

}  // namespace shard::scene_detail
