#pragma once
// The quasi-static check of docs/explanation/four-point-bending.md: the result must not change when the loading rate
// is halved. Two runs of the same packing (same seed) at rate v and at v/2 are compared on the
// figures calibration uses: F_max and the initial stiffness k (hence E by eq. 14).
#include <string>

#include "shard/bending/curve_analysis.hpp"

namespace shard::bending {

struct RateCheckCriteria {
  double force_max = 0.03;  // |F_max(v/2) / F_max(v) - 1| must stay below this (issue #6)
  double stiffness = 0.02;  // |k(v/2) / k(v) - 1| ... below this
};

struct RateCheck {
  double force_max_change = 0;   // F_max(slow) / F_max(fast) - 1
  double stiffness_change = 0;   // k(slow) / k(fast) - 1
  double deflection_change = 0;  // w_s,max(slow) / w_s,max(fast) - 1 (reported, not judged)
  bool force_max_ok = false, stiffness_ok = false;
  bool both_failed = false;      // both runs broke: F_max is a strength, not a stopping value
  bool passed() const { return force_max_ok && stiffness_ok && both_failed; }
};

// Throws std::invalid_argument when a run has no positive F_max or stiffness.
RateCheck compare_rates(const CurveAnalysis& fast, const CurveAnalysis& slow, const RateCheckCriteria& criteria = {});

// Several lines for the terminal: both runs' figures, the changes and the verdicts.
std::string format_rate_check(const CurveAnalysis& fast, const CurveAnalysis& slow, double fast_speed,
                              double slow_speed, const RateCheck& check, const RateCheckCriteria& criteria);

}  // namespace shard::bending
