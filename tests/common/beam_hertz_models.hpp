#pragma once
// Hertz-Mindlin contacts and beam bonds with their default (seed Table I) parameters, loaded from
// this build's plugin folder: the models of the hand-built bonded blocks in the step tests.
#include <memory>

#include "shard/bond_model.hpp"
#include "shard/contact_model.hpp"
#include "shard/plugin_host.hpp"

namespace shard::testing {

struct BeamHertzModels {
  PluginHost host;  // first: the libraries outlive the models
  std::unique_ptr<ContactModel> contact;
  std::unique_ptr<BondModel> bond;
  BeamHertzModels() {
    host.load_file(SHARD_BUILD_DIR "/plugins/shard_hertz_mindlin.so");
    host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
    contact = host.make_contact("hertz_mindlin", host.params(PluginKind::Contact, "hertz_mindlin", {}));
    bond = host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", {}));
  }
};

}  // namespace shard::testing
