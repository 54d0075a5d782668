#pragma once
// A measurement set's specimens by loading rate: specimens at one rate are replicates, and a
// model is simulated at each rate and judged on all of them.
#include <algorithm>
#include <cmath>
#include <vector>

#include "shard/measure/measurements.hpp"

namespace shard::measure {

// Two loading rates are one when they agree to 1e-9 (a rate read back from text or scaled).
inline bool same_rate(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }

std::vector<Specimen> specimens_at_rate(const MeasurementSet& set, double rate);

// The measured specimens grouped by loading rate (ascending): only `rate` when it is > 0,
// otherwise every rate in the set. A model is simulated at each rate and judged on all of them,
// so a rate effect (bond viscosity) shows as a difference between the groups.
struct RateGroups {
  std::vector<double> rates;
  std::vector<std::vector<Specimen>> specimens;
};
RateGroups rate_groups(const MeasurementSet& set, double rate);

}  // namespace shard::measure
