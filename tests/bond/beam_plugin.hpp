#pragma once
// The beam bond as the product uses it: loaded from shard_beam_bond.so through the PluginHost.
#include <map>
#include <memory>
#include <string>

#include "shard/plugin_host.hpp"

namespace shard::test {

class BeamPlugin {
 public:
  explicit BeamPlugin(const std::map<std::string, ParamValue>& values) {
    host_.load_file(std::string(SHARD_BUILD_DIR) + "/plugins/shard_beam_bond.so");
    params_ = host_.params(PluginKind::Bond, "beam_bond", values);
    model_ = host_.make_bond("beam_bond", params_);
  }
  const BondModel& model() const { return *model_; }
  const ParamSet& params() const { return params_; }

 private:
  PluginHost host_;  // declared first: the library outlives the model it made
  ParamSet params_;
  std::unique_ptr<BondModel> model_;
};

}  // namespace shard::test
