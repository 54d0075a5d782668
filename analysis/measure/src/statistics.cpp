#include "shard/measure/statistics.hpp"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>

namespace shard::measure {
namespace {

// Regularised lower incomplete gamma P(a, x) by its series (x < a + 1) and the upper Q(a, x) by
// Lentz's continued fraction (x >= a + 1), the standard split for fast convergence of both.
double lower_series(double a, double x) {
  double term = 1 / a, sum = term;
  for (int n = 1; n < 1000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-15) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

double upper_fraction(double a, double x) {
  const double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double chi_square_survival(double x, double dof) {
  if (!(dof > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (x <= 0) return 1;
  const double a = dof / 2, y = x / 2;
  return y < a + 1 ? 1 - lower_series(a, y) : upper_fraction(a, y);
}

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

}  // namespace shard::measure
