#include "shard/measure/features.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace shard::measure {
namespace {

constexpr double kElasticLow = 0.10, kElasticHigh = 0.60;  // fractions of F_max bounding the elastic fit
// A load drop counts when it exceeds 2 % of F_max (a burst of breaks, not a single bond of a
// resolved beam) and 5 force standard uncertainties (the running maximum of n noisy readings
// sits ~3 sigma above their mean for n ~ 1000; 5 keeps noise from counting).
constexpr double kDropFraction = 0.02, kDropNoise = 5.0;
constexpr double kFailureFraction = 0.5;  // failure: the force has fallen to half of F_max

// Linear interpolation of w between rows k - 1 and k where the force crosses `level`.
double crossing(const Curve& c, std::size_t k, double level) {
  if (k == 0) return c.displacement[0];
  const double f0 = c.force[k - 1], f1 = c.force[k];
  const double t = f0 != f1 ? std::clamp((f0 - level) / (f0 - f1), 0.0, 1.0) : 1.0;
  return c.displacement[k - 1] + t * (c.displacement[k] - c.displacement[k - 1]);
}

// Trapezoidal integral of F dw over rows [first, last].
double work(const Curve& c, std::size_t first, std::size_t last) {
  double w = 0;
  for (std::size_t k = first + 1; k <= last && k < c.size(); ++k)
    w += 0.5 * (c.force[k] + c.force[k - 1]) * (c.displacement[k] - c.displacement[k - 1]);
  return w;
}

double work_uncertainty(const Curve& c, std::size_t first, std::size_t last) {
  // Independent force readings: each enters with the width of its trapezoid strip.
  double var = 0;
  for (std::size_t k = first; k <= last && k < c.size(); ++k) {
    const double left = k > first ? c.displacement[k] - c.displacement[k - 1] : 0;
    const double right = k < last ? c.displacement[k + 1] - c.displacement[k] : 0;
    const double strip = 0.5 * (left + right);
    var += strip * strip * c.u_force[k] * c.u_force[k];
  }
  return std::sqrt(var);
}

}  // namespace

std::string_view feature_name(Feature f) {
  switch (f) {
    case Feature::Stiffness: return "stiffness";
    case Feature::PeakForce: return "peak_force";
    case Feature::PeakDisplacement: return "peak_displacement";
    case Feature::WorkToPeak: return "work_to_peak";
    case Feature::Nonlinearity: return "nonlinearity";
    case Feature::PostPeakWork: return "post_peak_work";
    case Feature::CrackPosition: return "crack_position";
    case Feature::FragmentX50: return "fragment_x50";
    case Feature::FragmentCount: return "fragment_count";
    case Feature::InitiationForce: return "initiation_force";
    case Feature::Oscillations: return "oscillations";
    case Feature::FailureDisplacement: return "failure_displacement";
  }
  return "?";
}

std::string_view feature_unit(Feature f) {
  switch (f) {
    case Feature::Stiffness: return "N/m";
    case Feature::PeakForce: return "N";
    case Feature::PeakDisplacement: return "m";
    case Feature::WorkToPeak: return "J";
    case Feature::Nonlinearity: return "1";
    case Feature::PostPeakWork: return "J";
    case Feature::CrackPosition: return "m";
    case Feature::FragmentX50: return "m";
    case Feature::FragmentCount: return "1";
    case Feature::InitiationForce: return "N";
    case Feature::Oscillations: return "1";
    case Feature::FailureDisplacement: return "m";
  }
  return "?";
}

Feature feature_at(std::size_t index) {
  if (index >= kFeatureCount) throw std::out_of_range("feature index");
  return static_cast<Feature>(index);
}

bool judged_by_default(Feature f) {
  return static_cast<std::size_t>(f) <= static_cast<std::size_t>(Feature::PostPeakWork);
}

bool fracture_feature(Feature f) {
  return f == Feature::CrackPosition || f == Feature::FragmentX50 || f == Feature::FragmentCount ||
         f == Feature::InitiationForce || f == Feature::FailureDisplacement;
}

double significant_drop(const Curve& c) {
  double u = 0;
  for (double x : c.u_force) u = std::max(u, x);
  return std::max(kDropFraction * c.force[peak_index(c)], kDropNoise * u);
}

std::size_t peak_index(const Curve& c) {
  if (c.size() == 0) throw std::invalid_argument("empty curve");
  return static_cast<std::size_t>(std::max_element(c.force.begin(), c.force.end()) - c.force.begin());
}

namespace {

// The least-squares line through the rows of the rise; with fewer than two, the secant between the
// last point below and the first point above `middle`, so that the fit is still a slope of the
// rising branch of a coarse curve.
ElasticFit line_through(const Curve& c, std::vector<std::size_t> rows, double middle) {
  const std::size_t p = peak_index(c);
  if (rows.size() < 2) {
    std::size_t above = 0;
    while (above < p && c.force[above] < middle) ++above;
    rows = {above > 0 ? above - 1 : 0, std::max<std::size_t>(above, 1)};
  }
  const double n = static_cast<double>(rows.size());
  double mw = 0, mf = 0;
  for (auto k : rows) mw += c.displacement[k] / n, mf += c.force[k] / n;
  double sww = 0, swf = 0, uf2 = 0;
  for (auto k : rows) {
    sww += (c.displacement[k] - mw) * (c.displacement[k] - mw);
    swf += (c.displacement[k] - mw) * (c.force[k] - mf);
    uf2 += c.u_force[k] * c.u_force[k] / n;
  }
  ElasticFit fit;
  if (!(sww > 0)) return fit;
  fit.stiffness = swf / sww;
  fit.toe_offset = fit.stiffness != 0 ? mw - mf / fit.stiffness : 0;
  fit.u_stiffness = std::sqrt(uf2 / sww);
  return fit;
}

}  // namespace

ElasticFit elastic_fit(const Curve& c) {
  const std::size_t p = peak_index(c);
  const double f_max = c.force[p];
  std::vector<std::size_t> rows;
  for (std::size_t k = 0; k <= p; ++k)
    if (c.force[k] >= kElasticLow * f_max && c.force[k] <= kElasticHigh * f_max) rows.push_back(k);
  return line_through(c, std::move(rows), 0.5 * f_max);
}

ElasticFit elastic_fit_between(const Curve& c, double low, double high) {
  const std::size_t p = peak_index(c);
  std::size_t first = 0;
  while (first < p && c.force[first] < low) ++first;
  std::vector<std::size_t> rows;
  for (std::size_t k = first; k <= p && c.force[k] <= high; ++k) rows.push_back(k);
  return line_through(c, std::move(rows), 0.5 * (low + high));
}

FeatureValues curve_features(const Curve& c) {
  FeatureValues f;
  const std::size_t p = peak_index(c);
  const ElasticFit fit = elastic_fit(c);
  const double f_max = c.force[p];
  const double w_peak = c.displacement[p];
  f[Feature::Stiffness] = fit.stiffness;
  f.sensor_uncertainty[0] = fit.u_stiffness;
  f[Feature::PeakForce] = f_max;
  f.sensor_uncertainty[1] = c.u_force[p];
  f[Feature::PeakDisplacement] = w_peak;
  f.sensor_uncertainty[2] = c.u_displacement[p];
  f[Feature::WorkToPeak] = work(c, 0, p);
  f.sensor_uncertainty[3] = work_uncertainty(c, 0, p);
  const double elastic_force_at_peak = fit.force_at(w_peak);
  f[Feature::Nonlinearity] = fit.nonlinearity(f_max, w_peak);
  // d(nonlinearity) / dF_max = -1 / (k (w_peak - w0)); the stiffness term is a second-order effect.
  f.sensor_uncertainty[4] = elastic_force_at_peak > 0 ? c.u_force[p] / elastic_force_at_peak : 0.0;
  f[Feature::PostPeakWork] = work(c, p, c.size() - 1);
  f.sensor_uncertainty[5] = work_uncertainty(c, p, c.size() - 1);

  const double drop = significant_drop(c);
  const CrackInitiation initiation = crack_initiation(c);
  f[Feature::InitiationForce] = initiation.force;
  f.sensor_uncertainty[static_cast<std::size_t>(Feature::InitiationForce)] = c.u_force[initiation.index];

  // Zig-zag count after the peak: a reversal is recorded once the force has moved by more than
  // `drop` against the current direction from the last extreme.
  double extreme = f_max;
  int direction = -1, reversals = 0;
  for (std::size_t k = p + 1; k < c.size(); ++k) {
    const double x = c.force[k];
    if (direction < 0 ? x < extreme : x > extreme) {
      extreme = x;
    } else if (std::abs(x - extreme) > drop) {
      direction = -direction;
      extreme = x;
      ++reversals;
    }
  }
  f[Feature::Oscillations] = reversals;

  std::size_t fail = p;
  while (fail < c.size() && c.force[fail] > kFailureFraction * f_max) ++fail;
  const std::size_t at = std::min(fail, c.size() - 1);
  f[Feature::FailureDisplacement] = fail < c.size() ? crossing(c, fail, kFailureFraction * f_max) : c.displacement.back();
  f.sensor_uncertainty[static_cast<std::size_t>(Feature::FailureDisplacement)] = c.u_displacement[at];
  return f;
}

namespace {

// Whether the curve, having left `line` by more than `drop` at row `from`, stays off it until the
// peak or until the load drops by `drop` below its running maximum (the crack that follows
// damage): damage is lasting. A departure the curve recovers from, coming back within half the
// threshold of the line, is a swing about it, not damage: a specimen loaded at speed rings about
// its elastic line, by more than 2 % of F_max, long before it cracks.
bool departure_lasts(const Curve& c, const ElasticFit& line, std::size_t from, std::size_t top, double drop) {
  const std::size_t peak = peak_index(c);
  for (std::size_t k = from; k <= peak; ++k) {
    if (c.force[k] > c.force[top]) top = k;
    if (c.force[top] - c.force[k] > drop) return true;
    if (c.force[k] >= line.force_at(c.displacement[k]) - 0.5 * drop) return false;
  }
  return true;
}

}  // namespace

CrackInitiation crack_initiation(const Curve& c) {
  const double drop = significant_drop(c);
  const ElasticFit line = elastic_fit(c);
  // The line is judged from the middle of its fit window on: below it a seating toe, a ramp or
  // the first points of a coarse record bend away from a line that they did not determine.
  const double f_max = c.force[peak_index(c)];
  const double line_from = 0.5 * (kElasticLow + kElasticHigh) * f_max;
  // A drop in the seating toe is the pins and rollers finding their contact (a bounce when they
  // meet the specimen at speed), not a crack: drops count from the line's fit window up.
  const double drops_from = kElasticLow * f_max;
  std::size_t top = 0;  // row of the running maximum
  std::size_t k = 0;
  for (; k < c.size(); ++k) {
    if (c.force[k] > c.force[top]) top = k;
    if (c.force[top] > drops_from && c.force[top] - c.force[k] > drop) break;
    const double on_line = line.force_at(c.displacement[k]);
    if (c.force[k] > line_from && on_line - c.force[k] > drop && departure_lasts(c, line, k, top, drop)) break;
  }
  // The last point before the break: the running maximum after a drop, the previous point after
  // a departure from the line.
  const std::size_t at = k == c.size() || k == 0 ? top : std::min(top, k - 1);
  return {at, c.force[at], c.displacement[at]};
}

double fragment_x50(const std::vector<double>& sizes, const std::vector<double>& masses) {
  if (sizes.empty()) throw std::invalid_argument("no fragments");
  std::vector<std::size_t> order(sizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return sizes[a] < sizes[b]; });
  auto mass = [&](std::size_t k) { return masses.empty() ? sizes[k] * sizes[k] * sizes[k] : masses[k]; };
  double total = 0;
  for (auto k : order) total += mass(k);
  double below = 0;
  for (auto k : order) {
    below += mass(k);
    if (below >= 0.5 * total) return sizes[k];
  }
  return sizes[order.back()];
}

}  // namespace shard::measure
