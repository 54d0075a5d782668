#include "shard/analysis/binomial_interval.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shard::analysis {

Interval wilson_interval(std::size_t successes, std::size_t trials, double z) {
  if (successes > trials) throw std::invalid_argument("wilson_interval: more successes than trials");
  if (!(z > 0)) throw std::invalid_argument("wilson_interval: z must be positive");
  if (trials == 0) return {0.0, 1.0};
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z2 = z * z;
  const double centre = (static_cast<double>(successes) + 0.5 * z2) / (n + z2);
  const double half = z * std::sqrt(n) / (n + z2) * std::sqrt(p * (1 - p) + z2 / (4 * n));
  // At k = 0 (k = n) the lower (upper) bound is 0 (1) exactly; rounding must not move it.
  const double lower = successes == 0 ? 0.0 : std::max(0.0, centre - half);
  const double upper = successes == trials ? 1.0 : std::min(1.0, centre + half);
  return {lower, upper};
}

}  // namespace shard::analysis
