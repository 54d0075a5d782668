#pragma once
// What a run throws when it blows up numerically (the watch: driver/src/health_watch.hpp).
#include <stdexcept>

namespace shard {

class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace shard
