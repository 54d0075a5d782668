#include "scene_setup.hpp"

#include <filesystem>

namespace shard::bench {

LoadedScene::LoadedScene(const std::string& file, const std::vector<std::string>& overrides) {
  host.load_directories(PluginHost::default_search_path());
  scene = load_scene(std::filesystem::path(file), overrides, host);
  instance = instantiate(scene, host, nullptr);
}

SimulationSetup LoadedScene::setup() const {
  const Simulation& sim = *instance.simulation;
  SimulationSetup s;
  s.particles = sim.particles();
  for (std::size_t b = 0; b < sim.bonds().size(); ++b) s.bonds.emplace_back(sim.bonds().i[b], sim.bonds().j[b]);
  s.contact = instance.contact.get();
  s.bond = instance.bond.get();
  s.breakage = scene.breakage;
  s.walls = scene.walls;
  s.gravity = scene.gravity;
  s.dt = sim.dt();
  s.materials = scene.material_table ? scene.materials.size() : 1;
  s.skin = scene.skin;
  s.global_damping = scene.global_damping;
  return s;
}

}  // namespace shard::bench
