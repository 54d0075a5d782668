#include "shard/bending/crack_location.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace shard::bending {
namespace {

// Median of a sorted, non-empty range (mean of the middle two for an even count).
double sorted_quantile(const std::vector<double>& s, double q) {
  const double pos = q * static_cast<double>(s.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = std::min(lo + 1, s.size() - 1);
  return s[lo] + (pos - static_cast<double>(lo)) * (s[hi] - s[lo]);
}

}  // namespace

CrackLocation locate_crack(std::span<const Vec3> midpoints, const Vec3& centre, const Vec3& axis, double window,
                           double pin_distance) {
  if (!(window > 0)) throw std::invalid_argument("locate_crack: the window must be a positive length");
  if (!(axis.norm() > 0)) throw std::invalid_argument("locate_crack: the beam axis is the zero vector");
  const Vec3 e = axis.normalized();
  CrackLocation c;
  c.window = window;
  c.breaks = midpoints.size();
  if (midpoints.empty()) return c;
  std::vector<double> s;
  s.reserve(midpoints.size());
  for (const auto& m : midpoints) s.push_back((m - centre).dot(e));
  std::sort(s.begin(), s.end());
  // Two pointers: for each left end, the furthest break within `window`.
  std::size_t best_lo = 0, best_hi = 0, hi = 0;
  for (std::size_t lo = 0; lo < s.size(); ++lo) {
    hi = std::max(hi, lo);
    while (hi + 1 < s.size() && s[hi + 1] - s[lo] <= window) ++hi;
    if (hi - lo > best_hi - best_lo) {
      best_lo = lo;
      best_hi = hi;
    }
  }
  const std::vector<double> cluster(s.begin() + static_cast<std::ptrdiff_t>(best_lo),
                                    s.begin() + static_cast<std::ptrdiff_t>(best_hi) + 1);
  c.found = true;
  c.cluster_breaks = cluster.size();
  c.position = sorted_quantile(cluster, 0.5);
  c.spread = sorted_quantile(s, 0.75) - sorted_quantile(s, 0.25);
  c.between_pins = std::abs(c.position) <= 0.5 * pin_distance;
  return c;
}

}  // namespace shard::bending
