#include "shard/measure/simulator.hpp"

#include <fmt/format.h>

#include <cmath>
#include <ostream>

#include "shard/measure/significant_digits.hpp"
#include "shard/measure/synthetic.hpp"
#include "shard/measure/test_conditions.hpp"

namespace shard::measure {

ModelPlan with_diameters_scaled(const Simulator& simulator, ModelPlan model, double factor) {
  for (const char* key : {"generator.diameter_min", "generator.diameter_max"})
    model.overrides.push_back({key, significant(factor * simulator.parameter(model, key), 9)});
  return model;
}

ModelPlan at_grain_size(const Simulator& simulator, const ModelPlan& model, double grain, std::ostream& log) {
  const double mean = 0.5 * (simulator.parameter(model, "generator.diameter_min") +
                             simulator.parameter(model, "generator.diameter_max"));
  const double factor = grain / mean;
  log << fmt::format("model at the lab's grain size {:.3g} mm: diameters x {:.3g} (mean {:.3g} mm), about {:.2g}x the "
                     "spheres and {:.2g}x the cost of a run\n",
                     1e3 * grain, factor, 1e3 * mean, std::pow(factor, -3), std::pow(factor, -4));
  return with_diameters_scaled(simulator, model, factor);
}

Specimen recorded_as_tested(Specimen run, const ModelPlan& model, const TestConditions& test, const std::string& what) {
  if (model.machine_compliance > 0) run.curve = with_machine_compliance(run.curve, model.machine_compliance);
  // Zeroed as the lab zeroed its curves: the machine's compliance is in what it recorded.
  if (test.seating_preload > 0) run.curve = zeroed_at_preload(run.curve, test.seating_preload, what);
  std::erase_if(run.fragment_sizes, [&](double d) { return d < test.fragment_size_threshold; });
  run.fragment_count.reset();
  if (!run.fragment_sizes.empty()) run.fragment_count = static_cast<double>(run.fragment_sizes.size());
  return run;
}

}  // namespace shard::measure
