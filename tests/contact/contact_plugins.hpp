#pragma once
// The contact models as the product ships them: loaded from the plugin shared objects of this
// build tree through shard::PluginHost, parameters validated against the declared schema.
#include <map>
#include <memory>
#include <string>

#include "shard/plugin_host.hpp"

namespace shard::test {

class ContactPlugins {
 public:
  ContactPlugins() {
    host_.load_file(SHARD_BUILD_DIR "/plugins/shard_hertz_mindlin.so");
    host_.load_file(SHARD_BUILD_DIR "/plugins/shard_linear_spring.so");
  }

  // The model must not outlive this object: its code lives in the loaded library.
  std::unique_ptr<ContactModel> make(const std::string& name,
                                     const std::map<std::string, ParamValue>& values = {}) const {
    return host_.make_contact(name, host_.params(PluginKind::Contact, name, values));
  }

  const PluginInfo& info(const std::string& name) const { return host_.find(PluginKind::Contact, name).info; }
  const PluginHost& host() const { return host_; }

 private:
  PluginHost host_;
};

}  // namespace shard::test
