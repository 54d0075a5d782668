#pragma once
// The plugins on the default search path (this build's plugin folder), loaded once per test
// binary: what a scene file names is found as `shard run` finds it.
#include "shard/plugin_host.hpp"

namespace shard::testing {

inline const PluginHost& plugins() {
  static PluginHost host;
  static const bool loaded = (host.load_directories(PluginHost::default_search_path()), true);
  (void)loaded;
  return host;
}

}  // namespace shard::testing
