#pragma once
// The benchmark's problems as SimulationSetups: a scene file through the kernel's scene loader and
// generator plugins (e.g. the seed beam), or bench_kernel's bonded block.
#include <memory>
#include <string>
#include <vector>

#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"
#include "shard/simulation.hpp"

namespace shard::bench {

// A scene file loaded and generated as `shard run` does it, with `overrides` ("section.key=value").
// `instance.simulation` is the serial run of the whole scene (the OpenMP reference); `setup()` is
// its state (particles, ids, flags, bonds) for a decomposed run, which then starts from the same
// state. The models live in `instance`.
struct LoadedScene {
  PluginHost host;
  Scene scene;
  SceneInstance instance;
  LoadedScene(const std::string& file, const std::vector<std::string>& overrides);
  SimulationSetup setup() const;
};

}  // namespace shard::bench
