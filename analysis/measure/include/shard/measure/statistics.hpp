#pragma once
// The few distribution functions the comparison and the diagnosis need.
#include <span>

namespace shard::measure {

// P(X > x) for X ~ chi-square with `dof` degrees of freedom (regularised upper incomplete gamma).
double chi_square_survival(double x, double dof);
// Two-sided p-value of a standard normal score z.
double normal_two_sided(double z);

double mean(std::span<const double> x);
// Sample standard deviation (n - 1); 0 for fewer than two values.
double sample_sd(std::span<const double> x);

}  // namespace shard::measure
