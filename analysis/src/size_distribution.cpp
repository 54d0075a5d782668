#include "shard/analysis/size_distribution.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace shard::analysis {

double characteristic_size(const std::vector<DistributionPoint>& points, double p) {
  if (!(p > 0.0 && p <= 1.0)) throw std::invalid_argument("characteristic_size: p outside (0, 1]");
  if (points.empty()) return 0.0;
  if (p <= points.front().cumulative) return points.front().d;
  for (std::size_t k = 1; k < points.size(); ++k) {
    const DistributionPoint& lo = points[k - 1];
    const DistributionPoint& hi = points[k];
    if (p <= hi.cumulative) {
      const double t = (p - lo.cumulative) / (hi.cumulative - lo.cumulative);
      return lo.d + t * (hi.d - lo.d);
    }
  }
  return points.back().d;  // p above the last Q by rounding only (Q_K is 1)
}

SizeDistribution size_distribution(std::span<const double> d, std::span<const double> mass,
                                   double fines_size) {
  if (d.size() != mass.size()) throw std::invalid_argument("size_distribution: d and mass differ in length");
  SizeDistribution fsd;
  fsd.fragments = d.size();
  fsd.fines_size = fines_size;
  if (d.empty()) return fsd;
  std::vector<std::size_t> order(d.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return d[a] < d[b]; });
  for (double m : mass) {
    if (!(m >= 0.0)) throw std::invalid_argument("size_distribution: negative or NaN mass");
  }
  // Sum in ascending-d order so Q_K is exactly the total used for normalising.
  double running = 0;
  std::vector<double> cumulative_mass;
  for (std::size_t k : order) {
    running += mass[k];
    if (!fsd.points.empty() && fsd.points.back().d == d[k]) {
      cumulative_mass.back() = running;
    } else {
      fsd.points.push_back({d[k], 0.0});
      cumulative_mass.push_back(running);
    }
    if (d[k] < fines_size) fsd.fines_mass += mass[k];
  }
  fsd.total_mass = running;
  if (!(fsd.total_mass > 0)) throw std::invalid_argument("size_distribution: total mass is zero");
  for (std::size_t k = 0; k < fsd.points.size(); ++k) {
    fsd.points[k].cumulative = cumulative_mass[k] / fsd.total_mass;
  }
  fsd.points.back().cumulative = 1.0;
  fsd.x10 = characteristic_size(fsd.points, 0.1);
  fsd.x50 = characteristic_size(fsd.points, 0.5);
  fsd.x90 = characteristic_size(fsd.points, 0.9);
  return fsd;
}

SizeDistribution size_distribution(const std::vector<Fragment>& fragments, double fines_size) {
  std::vector<double> d(fragments.size()), mass(fragments.size());
  for (std::size_t k = 0; k < fragments.size(); ++k) {
    d[k] = fragments[k].d_eq;
    mass[k] = fragments[k].mass;
  }
  return size_distribution(d, mass, fines_size);
}

}  // namespace shard::analysis
