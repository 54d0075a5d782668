// Registers the "from_file" generator.
#include "from_file.hpp"
#include "shard/plugin.hpp"

SHARD_PLUGIN(registrar) {
  registrar->add_generator(
      {shard::PluginKind::Generator, "from_file", "1.0",
       "reloads a stored packing (CSV spheres and bonds, e.g. saved by stl_fill)", shard::from_file::from_file_params()},
      [](const shard::ParamSet& params) -> std::unique_ptr<shard::Generator> {
        return std::make_unique<shard::from_file::FromFile>(shard::from_file::from_file_settings(params));
      });
}
