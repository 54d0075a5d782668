#pragma once
// One model held against every loading rate of one measurement set: the single-set diagnosis
// (set_diagnosis.hpp) and calibration (effect_calibration.hpp) score their runs this way.
#include <iosfwd>
#include <vector>

#include "shard/measure/comparison.hpp"
#include "shard/measure/model_plan.hpp"
#include "shard/measure/rate_groups.hpp"
#include "shard/measure/simulator.hpp"

namespace shard::measure {

// One model against every rate group: the joint residual vector is the per-rate vectors one
// after the other (components named "<name>@<rate>" when there are several rates); the NRMSE
// is the RMS of the per-rate NRMSEs.
struct RateComparison {
  std::vector<double> rates;
  std::vector<Comparison> at;
  // Each packing seed's runs compared alone, [seed][rate] (none for a single seed).
  std::vector<std::vector<Comparison>> seed_at;
  ResidualVector residual_vector() const;
  // One seed's residual vector in the units of `band`'s (the ensemble's band: the same
  // standardisation as band.residual_vector()).
  ResidualVector seed_residual_vector(std::size_t seed, const RateComparison& band) const;
  std::vector<ResidualVector> seed_residual_vectors(const RateComparison& band) const;  // every seed's, as above
  double nrmse() const;
  double noise_nrmse() const;  // RMS of the per-rate Comparison::noise_nrmse
  double chi_square() const;
};

// What a model of one set is held against: the measured specimens by rate, the set's metadata
// (its test conditions), and how each component is scored.
struct MeasuredRates {
  RateGroups groups;
  Metadata metadata;
  CompareOptions compare;
  // Its loading rates, at the scene's one specimen size (DataCoverage::sizes).
  DataCoverage coverage() const { return DataCoverage{groups.rates.size(), 1}; }
};

// Simulates every model at every rate of the data (one batch) and compares. The first call takes
// the data's test conditions (Simulator::check_inputs).
std::vector<RateComparison> simulate_and_compare(Simulator& simulator, const MeasuredRates& data,
                                                 const std::vector<ModelPlan>& models, std::ostream& log);

}  // namespace shard::measure
