// Registers the "box_fill" generator.
#include "box_fill.hpp"
#include "shard/plugin.hpp"

SHARD_PLUGIN(registrar) {
  registrar->add_generator(
      {shard::PluginKind::Generator, "box_fill", "1.0",
       "spheres in an axis-aligned box: fcc/hcp/cubic lattice or seeded advancing-front packing",
       shard::box_fill::box_fill_params()},
      [](const shard::ParamSet& params) -> std::unique_ptr<shard::Generator> {
        return std::make_unique<shard::box_fill::BoxFill>(shard::box_fill::box_fill_settings(params));
      });
}
