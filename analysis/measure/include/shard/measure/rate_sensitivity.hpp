#pragma once
// Does a set tested at several loading rates tell whether its strength depends on the rate?
//
// A strength difference found at one rate has two kinds of cause. Rate-independent ones: a batch
// with weaker or more scattered bonds, damage before the peak. Or a rate-dependent strength:
// subcritical crack growth (crack speed ~ K^n) makes a brittle body's strength grow with the
// loading rate as rate^(1/(n+1)) (Charles' law), with n about 10-50 for glass, ceramics, rock and
// cement-based materials. At one rate the two look alike. A lab that tests a batch at two rates
// asks exactly which of them it has, so a rate-independent name for its strength difference
// claims that the strength does not change with the rate. The set supports that claim only when
// its measured change between its slowest and fastest rate is known closely enough to exclude
// what subcritical growth would give over that span, and that change is nil within its interval;
// otherwise the name is withheld (require_resolved_rate_dependence in contrast_diagnosis.hpp).
#include <cmath>
#include <cstddef>

namespace shard::measure {

struct RateSensitivity {
  double slow_rate = 0, fast_rate = 0;  // m/s: the set's slowest and fastest rate
  // ln F_max of the set against the reference at the slow rate, and its standard uncertainty:
  // the strength difference whose rate dependence is asked about.
  double strength_contrast = 0, u_strength_contrast = 0;
  // ln F_max at the fast rate less at the slow rate, less the base model's own change between the
  // two rates (inertia, damping): the set's measured rate dependence of its strength.
  double change = 0;
  // Its standard uncertainty from the set's own specimens at each rate (their own scatter, not
  // the pooled one: a beam that fractures dynamically at the fast rate scatters wider there) and
  // the model's packing seeds; Welch-Satterthwaite degrees of freedom.
  double u_change = 0, dof = 0;
  double half_width = 0;   // of the 95 % interval of `change`: t(0.975, dof) u_change
  double subcritical = 0;  // ln(fast / slow) / (n + 1): the change subcritical growth of exponent n gives
  double exponent = 0;     // that n
  std::size_t specimens_per_rate = 0;  // the fewer of the two rates' specimens

  // The strength differs from the reference's beyond twice its uncertainty.
  bool strength_differs() const { return u_strength_contrast > 0 && strength_contrast * strength_contrast > 4 * u_strength_contrast * u_strength_contrast; }
  // The 95 % interval of the change is narrower than the change subcritical growth would give.
  bool resolved() const { return half_width < subcritical; }
  // The 95 % interval of the change leaves out none: the set's strength changes with the rate.
  bool rate_dependent() const { return std::abs(change) > half_width; }
  // Specimens per rate that would bring the half-width to the subcritical change (at the same
  // scatter: the half-width falls as one over the square root of the count).
  std::size_t specimens_needed() const;
};

}  // namespace shard::measure
