#include "scene_setup.hpp"

#include <filesystem>

namespace shard::bench {

LoadedScene::LoadedScene(const std::string& file, const std::vector<std::string>& overrides) {
  host.load_directories(PluginHost::default_search_path());
  scene = load_scene(std::filesystem::path(file), overrides, host);
  instance = instantiate(scene, host, nullptr);
}

SimulationSetup LoadedScene::setup() const { return setup_of(scene, instance); }

}  // namespace shard::bench
