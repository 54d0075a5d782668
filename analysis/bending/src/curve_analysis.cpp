#include "shard/bending/curve_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shard::bending {

LinearFit fit_line(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) throw std::invalid_argument("fit_line: x and y differ in length");
  if (x.size() < 2) throw std::invalid_argument("fit_line: need at least two points");
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    mx += x[k];
    my += y[k];
  }
  mx /= n;
  my /= n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxx += (x[k] - mx) * (x[k] - mx);
    sxy += (x[k] - mx) * (y[k] - my);
    syy += (y[k] - my) * (y[k] - my);
  }
  if (sxx <= 0) throw std::invalid_argument("fit_line: all x are equal");
  LinearFit f;
  f.points = x.size();
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  f.r_squared = syy > 0 ? (sxy * sxy) / (sxx * syy) : 1.0;
  return f;
}

CurveAnalysis analyse_curve(std::span<const double> w, std::span<const double> f, const BendingGeometry& geometry,
                            const CurveOptions& options) {
  if (w.size() != f.size()) throw std::invalid_argument("load curve: displacement and force differ in length");
  if (w.empty()) throw std::invalid_argument("load curve: no rows");
  if (!(0 <= options.fit_low && options.fit_low < options.fit_high && options.fit_high <= 1))
    throw std::invalid_argument(fmt::format("load curve: the fit window {}-{} of F_max is not within 0-1",
                                            options.fit_low, options.fit_high));
  CurveAnalysis a;
  a.rows = w.size();
  a.fit_low = options.fit_low;
  a.fit_high = options.fit_high;
  a.peak_row = static_cast<std::size_t>(std::max_element(f.begin(), f.end()) - f.begin());
  a.force_max = f[a.peak_row];
  if (!(a.force_max > 0)) throw std::invalid_argument("load curve: the force never rises above zero");
  a.displacement_at_peak = w[a.peak_row];
  a.final_force = f.back();

  // The rising part: from the last row before the peak at which the force was still below the
  // window's lower bound (so seating chatter before it is ignored) up to the first row above the
  // upper bound.
  const double lo = options.fit_low * options.window_force(a.force_max);
  const double hi = options.fit_high * options.window_force(a.force_max);
  std::size_t first = 0;
  for (std::size_t k = 0; k <= a.peak_row; ++k)
    if (f[k] < lo) first = k + 1;
  std::vector<double> xs, ys;
  for (std::size_t k = first; k <= a.peak_row && f[k] <= hi; ++k) {
    xs.push_back(w[k]);
    ys.push_back(f[k]);
  }
  if (xs.size() < 3)
    throw std::invalid_argument(fmt::format(
        "load curve: only {} rows between {:.0f} % and {:.0f} % of {:.4g} N on the rising part; record the "
        "series more often (output.series_interval) or load more slowly",
        xs.size(), 100 * options.fit_low, 100 * options.fit_high, options.window_force(a.force_max)));
  a.fit = fit_line(xs, ys);
  a.stiffness = a.fit.slope;
  if (!(a.stiffness > 0)) throw std::invalid_argument("load curve: the force does not rise with the displacement");
  a.onset = -a.fit.intercept / a.stiffness;
  a.deflection_at_peak = a.displacement_at_peak - a.onset;
  a.youngs_modulus = youngs_modulus_from_stiffness(geometry, a.stiffness);
  a.youngs_modulus_secant =
      a.deflection_at_peak > 0 ? youngs_modulus_from_stiffness(geometry, a.force_max / a.deflection_at_peak) : 0.0;
  a.flexural_strength = flexural_stress(geometry, a.force_max);
  for (std::size_t k = a.peak_row; k < f.size(); ++k)
    if (f[k] < options.failure_drop * a.force_max) a.failed = true;
  a.peak_window = options.peak_window;
  // Centred window in travel, two pointers over rows of (mostly) increasing w.
  std::size_t lo_row = 0, hi_row = 0;
  double window_sum = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    while (hi_row < w.size() && w[hi_row] <= w[k] + 0.5 * options.peak_window) window_sum += f[hi_row++];
    while (lo_row < k && w[lo_row] < w[k] - 0.5 * options.peak_window) window_sum -= f[lo_row++];
    if (hi_row > lo_row) a.force_max_smoothed = std::max(a.force_max_smoothed, window_sum / static_cast<double>(hi_row - lo_row));
  }
  return a;
}

}  // namespace shard::bending
