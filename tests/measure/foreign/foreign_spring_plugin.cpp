// Registers the test-only foreign spring bond (not installed, not in the shipped plugin folder):
// load it with `shard --plugin-dir <build>/tests/measure/foreign/plugins`.
#include <memory>

#include "foreign_spring_bond.hpp"
#include "shard/plugin.hpp"

SHARD_PLUGIN(registrar) {
  shard::PluginInfo info;
  info.kind = shard::PluginKind::Bond;
  info.name = "foreign_spring_bond";
  info.version = "0.1.0-test";
  info.doc = "test only: linear n/s/b/t springs, force-based bpm breakage (a base model of another form)";
  info.params = shard::foreign::spring_bond_params();
  registrar->add_bond(std::move(info), [](const shard::ParamSet& p) -> std::unique_ptr<shard::BondModel> {
    return std::make_unique<shard::foreign::SpringBond>(shard::foreign::SpringBondParams::from(p));
  });
}
