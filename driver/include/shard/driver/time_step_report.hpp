#pragma once
// The time-step lines of a scene ready to run (docs/explanation/physics.md, "Time step"): each limit with its
// critical and recommended step, then the step taken and how many steps the duration needs.
// `shard run` prints them and stores the limits in run.h5's /notes; `shard check` prints them.
#include <string>
#include <utility>
#include <vector>

#include "shard/time_step.hpp"

namespace shard {
struct Scene;
class Simulation;
}  // namespace shard

namespace shard::driver {

struct TimeStepReport {
  std::vector<std::pair<std::string, std::string>> limits;  // ("dt_<limit>", line) per limit
  std::string chosen;                                       // "time step dt = ... s (auto), N steps for T s"
};

TimeStepReport time_step_report(const Scene& scene, const Simulation& sim);
// The same from the models' limits over the whole scene and the step its Simulation chose, s.
TimeStepReport time_step_report(const Scene& scene, const std::vector<TimeStepLimit>& limits, double dt);

}  // namespace shard::driver
