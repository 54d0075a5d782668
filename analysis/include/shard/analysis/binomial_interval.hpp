#pragma once
// Confidence interval of a proportion from k successes in n trials (the broken share of n plates).
//
// Wilson's score interval (Wilson 1927): the set of p for which |k/n - p| <= z sqrt(p (1 - p) / n),
//   centre = (k + z^2 / 2) / (n + z^2)
//   half   = z sqrt(n) / (n + z^2) * sqrt(p^ (1 - p^) + z^2 / (4 n)),   p^ = k / n
// It stays inside [0, 1], is not empty at k = 0 or k = n (where the normal "Wald" interval
// collapses to a point), and its coverage is close to nominal already for a handful of plates.
#include <cstddef>

namespace shard::analysis {

// z of a two-sided 95 % interval: the 0.975 quantile of the standard normal distribution.
inline constexpr double kZ95 = 1.959963984540054;

struct Interval {
  double lower = 0, upper = 0;
};

// n = 0 gives [0, 1] (nothing is known); throws std::invalid_argument when k > n or z <= 0.
Interval wilson_interval(std::size_t successes, std::size_t trials, double z = kZ95);

}  // namespace shard::analysis
