#pragma once
// Differences of two models run on the same packing seeds (common random numbers): what the
// contrast study and the rate sensitivity both take from simulated components.
#include <vector>

#include "shard/measure/statistics.hpp"

namespace shard::measure {

// Mean and variance of the mean over the seeds of a - b, component by component (rows: seeds).
inline void paired(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b,
                   std::vector<double>& mean, std::vector<double>& var_of_mean) {
  const std::size_t n = a.size(), m = a.front().size();
  mean.assign(m, 0.0);
  var_of_mean.assign(m, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    std::vector<double> d(n);
    for (std::size_t k = 0; k < n; ++k) d[k] = a[k][i] - b[k][i];
    mean[i] = measure::mean(d);
    const double s = sample_sd(d);
    var_of_mean[i] = s * s / static_cast<double>(n);
  }
}

}  // namespace shard::measure
