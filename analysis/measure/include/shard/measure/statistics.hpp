#pragma once
// The few distribution functions the comparison and the diagnosis need.
#include <span>

namespace shard::measure {

// P(X > x) for X ~ chi-square with `dof` degrees of freedom (Boost.Math's regularised upper
// incomplete gamma); NaN for a NaN x or dof <= 0.
double chi_square_survival(double x, double dof);
// The x with chi_square_survival(x, dof) = level (Boost.Math's inverse of the same gamma).
double chi_square_critical(double level, double dof);
// Two-sided p-value of a standard normal score z.
double normal_two_sided(double z);

// A variance of a mean difference, split into the parts estimated from samples (each with its
// degrees of freedom, n - 1) and a part known without sampling error (sensor noise): the
// Welch-Satterthwaite effective degrees of freedom of their sum,
//   nu = (sum v_i + v_known)^2 / sum (v_i^2 / nu_i).
// Infinite when nothing is estimated (the score is then exactly normal).
struct VarianceTerm {
  double variance = 0;
  double dof = 0;
};
double satterthwaite_dof(std::span<const VarianceTerm> estimated, double known_variance);

// The standard normal score with the same tail probability as Student's t with `dof` degrees of
// freedom: Phi^-1(F_t(t; nu)), sign kept. A difference standardised by variances estimated from
// three specimens and three replicates is t-distributed with 2-4 degrees of freedom; read as
// N(0, 1) its tails are far too heavy (t = 4.6 is p 0.01 at nu = 3, not 4e-6). Returns t for
// infinite dof.
double equivalent_normal_score(double t, double dof);
// The two-sided `level` quantile of Student's t with `dof` degrees of freedom (level 0.95: the
// t that bounds 95 % of draws in |t|); the normal quantile for infinite dof.
double student_t_quantile(double level, double dof);
// P(T > t) for Student's t with `dof` degrees of freedom (the normal's for infinite dof).
double student_t_upper_tail(double t, double dof);

double mean(std::span<const double> x);
// Sample standard deviation (n - 1); 0 for fewer than two values.
double sample_sd(std::span<const double> x);
// One-sided p that the mean of x is above zero (one-sample Student's t, n - 1 degrees of
// freedom): 1 for fewer than two values or a mean not above zero, 0 when every value is the same
// positive number.
double mean_above_zero_p(std::span<const double> x);

}  // namespace shard::measure
