#pragma once
#include <string>

namespace shard {

// One model's stability limit. `critical` is the textbook value (Rayleigh time, bond period
// estimate), `recommended` the step the model asks for (e.g. 0.2 t_Rayleigh, docs/explanation/physics.md).
struct TimeStepLimit {
  std::string name;
  double critical = 0;
  double recommended = 0;
};

}  // namespace shard
