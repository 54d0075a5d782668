#include "shard/measure/effect_scaling.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace shard::measure {

TestScales base_run_scales(const std::vector<std::vector<Curve>>& curves_by_rate) {
  std::vector<std::vector<Specimen>> groups;
  for (const auto& rate : curves_by_rate) {
    if (rate.empty()) continue;
    auto& group = groups.emplace_back();
    for (const auto& c : rate) {
      if (c.force.empty()) throw std::invalid_argument(fmt::format("base_run_scales: curve '{}' is empty", c.id));
      group.push_back(Specimen{});
      group.back().curve = c;
    }
  }
  if (groups.empty()) throw std::invalid_argument("base_run_scales: no simulated curve of the base run");
  return test_scales(groups, 1.0);
}

std::string describe_scaled_plausible(const std::vector<CandidateEffect>& effects, const TestScales& scales) {
  std::string out;
  for (const auto& e : effects)
    if (!e.plausible_from.empty())
      out += fmt::format("{} {:.3g} {} = {:g} x {} {:.3g}\n", e.name, e.plausible, e.unit, e.plausible_factor,
                         e.plausible_from, scales.at(e.plausible_from));
  return out;
}

}  // namespace shard::measure
