#pragma once
// The damping a contact law needs for a set coefficient of restitution, from the law's own
// restitution as a function of its damping. Both laws' e(damping) fall monotonically from 1 at no
// damping (more damping, less rebound), so the damping is bracketed by doubling from 1 and then
// bisected.
#include <stdexcept>

namespace shard::contact {

// The damping >= 0 with restitution_of(damping) == e, for 0 < e <= 1: bisected until the bracket is
// narrower than relative_tolerance of its upper end.
template <class RestitutionOf>
double damping_for_restitution(double e, RestitutionOf&& restitution_of, double relative_tolerance) {
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("restitution must lie in (0, 1]");
  if (e == 1.0) return 0.0;
  double low = 0.0;
  double high = 1.0;
  while (restitution_of(high) > e) {
    low = high;
    high *= 2.0;
    if (high > 1e6) throw std::invalid_argument("restitution too small to realise");
  }
  while (high - low > relative_tolerance * high) {
    const double mid = 0.5 * (low + high);
    (restitution_of(mid) > e ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace shard::contact
