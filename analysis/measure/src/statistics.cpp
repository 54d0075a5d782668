#include "shard/measure/statistics.hpp"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <limits>

namespace shard::measure {

double chi_square_survival(double x, double dof) {
  if (!(dof > 0) || std::isnan(x)) return std::numeric_limits<double>::quiet_NaN();
  if (x <= 0) return 1;
  if (std::isinf(x)) return 0;
  return boost::math::gamma_q(dof / 2, x / 2);  // the regularised upper incomplete gamma
}

double chi_square_critical(double level, double dof) { return 2 * boost::math::gamma_q_inv(dof / 2, level); }

double normal_two_sided(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

double satterthwaite_dof(std::span<const VarianceTerm> estimated, double known_variance) {
  double total = known_variance, denominator = 0;
  for (const auto& term : estimated) {
    total += term.variance;
    if (term.variance > 0 && term.dof > 0) denominator += term.variance * term.variance / term.dof;
  }
  if (!(denominator > 0)) return std::numeric_limits<double>::infinity();
  return total * total / denominator;
}

double equivalent_normal_score(double t, double dof) {
  if (!std::isfinite(t) || !(dof > 0) || std::isinf(dof)) return t;
  // Work in the tail of |t| so that large scores keep their precision (cdf near 1 would round).
  const double tail = boost::math::cdf(boost::math::complement(boost::math::students_t_distribution<double>(dof), std::abs(t)));
  if (!(tail > 0)) return t;  // beyond double precision: no finite normal equivalent is smaller
  const double z = boost::math::quantile(boost::math::complement(boost::math::normal_distribution<double>(), tail));
  return std::copysign(z, t);
}

double student_t_quantile(double level, double dof) {
  const double tail = 0.5 * (1 - level);
  if (std::isinf(dof)) return boost::math::quantile(boost::math::complement(boost::math::normal_distribution<double>(), tail));
  return boost::math::quantile(boost::math::complement(boost::math::students_t_distribution<double>(dof), tail));
}

double student_t_upper_tail(double t, double dof) {
  if (std::isinf(dof)) return boost::math::cdf(boost::math::complement(boost::math::normal_distribution<double>(), t));
  return boost::math::cdf(boost::math::complement(boost::math::students_t_distribution<double>(dof), t));
}

double mean(std::span<const double> x) {
  double s = 0;
  for (double v : x) s += v;
  return x.empty() ? 0 : s / static_cast<double>(x.size());
}

double sample_sd(std::span<const double> x) {
  if (x.size() < 2) return 0;
  const double m = mean(x);
  double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(x.size() - 1));
}

double mean_above_zero_p(std::span<const double> x) {
  if (x.size() < 2) return 1;
  const double m = mean(x), sd = sample_sd(x);
  if (!(m > 0)) return 1;
  if (sd == 0) return 0;
  const auto n = static_cast<double>(x.size());
  return student_t_upper_tail(m / (sd / std::sqrt(n)), n - 1);
}

}  // namespace shard::measure
