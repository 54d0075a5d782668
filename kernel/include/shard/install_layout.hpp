#pragma once
// Where Shard's own files are -- the shipped plugins, the plugin templates, the example scenes --
// found from where the running Shard library itself was loaded, never from a path fixed at build
// time: an installed tree works from any prefix and keeps working when moved, and an installed
// Shard never reads the build tree it was made in.
#include <filesystem>

namespace shard {

struct InstallLayout {
  std::filesystem::path plugin_dir;  // the plugins that ship with Shard
  std::filesystem::path data_dir;    // holds templates/ and scenes/
  bool build_tree = false;           // running from the build tree it was compiled in
};

// In the build tree (the library, or a test program that compiles this file in, sits where it
// was built): <build>/plugins and the source folder. Anywhere else: the install prefix around the
// library, <prefix>/<libdir>/shard/plugins and <prefix>/<datadir>/shard (GNUInstallDirs).
InstallLayout install_layout();

}  // namespace shard
