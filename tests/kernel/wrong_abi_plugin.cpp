// A plugin that claims an ABI the host does not speak.
#include "shard/plugin.hpp"

extern "C" __attribute__((visibility("default"))) int shard_plugin_abi() { return 999; }
extern "C" __attribute__((visibility("default"))) void shard_plugin_register(shard::Registrar*) {}
