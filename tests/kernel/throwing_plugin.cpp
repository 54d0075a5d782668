// A plugin whose registration fails.
#include <stdexcept>

#include "shard/plugin.hpp"

SHARD_PLUGIN(registrar) {
  (void)registrar;
  throw std::runtime_error("licence file not found");
}
