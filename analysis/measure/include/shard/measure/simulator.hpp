#pragma once
// What the measurement science asks of a simulator: the replicates of a batch of models, run and
// recorded as the lab ran and recorded its tests. The diagnoses (contrast_diagnosis.hpp) are
// functions over this interface, so their decision paths are tested with a simulator of analytic
// responses in milliseconds, and the DEM ensemble (the runs through the run driver, on threads,
// worker processes or MPI ranks) is one implementation of it.
#include <iosfwd>
#include <string>
#include <vector>

#include "shard/measure/effect_library.hpp"
#include "shard/measure/measurements.hpp"
#include "shard/measure/model_plan.hpp"

namespace shard::measure {

// How quasi-static the runs so far were, in the field's terms.
struct RunHealth {
  double max_kinetic_to_elastic = 0;        // the models of the data (not the probes)
  double max_probe_kinetic_to_elastic = 0;  // the effects' trials at their library sizes
  std::string dynamic_warning;              // empty while the runs are quasi-static
};

class Simulator {
 public:
  virtual ~Simulator() = default;
  // The replicates (one per packing seed, the same seeds for every model: common random numbers)
  // of every model, in one batch; throws with the first failed run's reason.
  virtual std::vector<std::vector<Specimen>> simulate(const std::vector<ModelPlan>& models, std::ostream& log) = 0;
  // Before the first simulation of a study: takes the data's test conditions (ramp, preload,
  // fragment threshold) and throws, naming both, when the specimens' geometry is not the model's.
  virtual void check_inputs(const ModelPlan& model, const std::vector<Specimen>& specimens,
                            const Metadata& metadata) = 0;
  // Throws the scene's own error (file, key, the fix) when `model`'s scene does not load with its
  // overrides: a model the study asks for only late (an assumption moved after the base fit) is
  // checked before the first run.
  virtual void check_model(const ModelPlan& model) = 0;
  // The value of a model's section.key parameter, and the range its plugin accepts.
  virtual double parameter(const ModelPlan& model, const std::string& key) const = 0;
  virtual ParameterRange parameter_range(const std::string& key) const = 0;
  virtual RunHealth health() const = 0;

  std::vector<Specimen> simulate_one(const ModelPlan& model, std::ostream& log) {
    return simulate(std::vector<ModelPlan>{model}, log).front();
  }
};

// The model with its packing's diameters (generator.diameter_min and _max) scaled by `factor`: a
// finer or coarser packing of the same body. A run costs about factor^-4 as much (factor^-3 the
// spheres, factor^-1 the time steps).
ModelPlan with_diameters_scaled(const Simulator& simulator, ModelPlan model, double factor);

// The model at the lab's reported grain size: diameters scaled so that their mean is `grain`
// (m). `log` gets the factor and the cost.
ModelPlan at_grain_size(const Simulator& simulator, const ModelPlan& model, double grain, std::ostream& log);

// A simulated run's curve recorded as the lab recorded its specimens: the machine's compliance in
// series, zeroed at the seating preload, fragments no smaller than the lab counts. `what` names
// the run in an error.
Specimen recorded_as_tested(Specimen run, const ModelPlan& model, const TestConditions& test, const std::string& what);

}  // namespace shard::measure
