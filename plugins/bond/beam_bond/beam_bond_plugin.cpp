// Registers the beam bond with the host: its name, version and parameters with SI units.
#include <memory>

#include "beam_bond_model.hpp"
#include "beam_bond_schema.hpp"
#include "shard/plugin.hpp"

namespace {

shard::PluginInfo beam_bond_info() {
  shard::PluginInfo info;
  info.kind = shard::PluginKind::Bond;
  info.name = "beam_bond";
  info.version = "1.1.0";  // 1.1: the effect policies (docs/reference/effects.md)
  info.doc = "Timoshenko beam bond, total quaternion formulation, von Mises breakage (seed eq. 3-12); effect policies "
             "weibull_strength, softening, viscosity, compression_asymmetry (docs/reference/effects.md)";
  info.params = shard::beam::beam_bond_params();
  return info;
}

}  // namespace

SHARD_PLUGIN(registrar) {
  registrar->add_bond(beam_bond_info(), [](const shard::ParamSet& p) -> std::unique_ptr<shard::BondModel> {
    return std::make_unique<shard::beam::BeamBond>(shard::beam::BeamBondParams::from(p));
  });
}
