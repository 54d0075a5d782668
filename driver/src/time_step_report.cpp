#include "shard/driver/time_step_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>

#include "shard/scene.hpp"
#include "shard/simulation.hpp"

namespace shard::driver {

TimeStepReport time_step_report(const Scene& scene, const Simulation& sim) {
  return time_step_report(scene, sim.time_step_limits(), sim.dt());
}

TimeStepReport time_step_report(const Scene& scene, const std::vector<TimeStepLimit>& limits, double dt) {
  TimeStepReport report;
  for (const auto& l : limits)
    report.limits.emplace_back("dt_" + l.name, fmt::format("time step limit {}: critical {:.4g} s, recommended {:.4g} s",
                                                           l.name, l.critical, l.recommended));
  report.chosen = fmt::format("time step dt = {:.4g} s ({}), {} steps for {:.4g} s", dt, scene.dt > 0 ? "set" : "auto",
                              static_cast<std::int64_t>(std::ceil(scene.duration / dt)), scene.duration);
  return report;
}

}  // namespace shard::driver
