#include "shard/measure/simulator.hpp"

#include "shard/measure/synthetic.hpp"
#include "shard/measure/test_conditions.hpp"

namespace shard::measure {

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
