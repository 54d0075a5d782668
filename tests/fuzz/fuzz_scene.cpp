// libFuzzer target: any byte string handed to the scene loader either loads or throws one of the
// documented error types (SceneError, PluginError, StlError). Anything else -- a crash, a
// sanitizer report, another exception type -- is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>

#include "shard/geometry/stl.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

namespace {

// The host is built once: loading plugins per input would dominate the run time. The scene
// loader only reads from it (find, validate), so inputs cannot influence each other through it.
const shard::PluginHost& host() {
  static const std::unique_ptr<shard::PluginHost> instance = [] {
    auto h = std::make_unique<shard::PluginHost>();
    h->load_directories(shard::PluginHost::default_search_path());
    return h;
  }();
  return *instance;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  host();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    shard::load_scene_text(text, "fuzz.toml", {}, host());
  } catch (const shard::SceneError&) {
  } catch (const shard::PluginError&) {
  } catch (const shard::geometry::StlError&) {
  }
  return 0;
}
