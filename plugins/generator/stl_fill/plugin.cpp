// Registers the "stl_fill" generator.
#include "shard/plugin.hpp"
#include "stl_fill.hpp"

SHARD_PLUGIN(registrar) {
  registrar->add_generator(
      {shard::PluginKind::Generator, "stl_fill", "1.0",
       "fills a closed STL body with bonded spheres by an advancing front (seed sec. III)",
       shard::stl_fill::stl_fill_params()},
      [](const shard::ParamSet& params) -> std::unique_ptr<shard::Generator> {
        return std::make_unique<shard::stl_fill::StlFill>(shard::stl_fill::stl_fill_settings(params));
      });
}
