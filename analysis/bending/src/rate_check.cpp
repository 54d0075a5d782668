#include "shard/bending/rate_check.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace shard::bending {

RateCheck compare_rates(const CurveAnalysis& fast, const CurveAnalysis& slow, const RateCheckCriteria& criteria) {
  if (!(fast.force_max > 0 && slow.force_max > 0 && fast.stiffness > 0 && slow.stiffness > 0))
    throw std::invalid_argument(fmt::format("rate check: both runs need a positive F_max and stiffness (fast: {:.4g} N, "
                                            "{:.4g} N/m; slow: {:.4g} N, {:.4g} N/m)",
                                            fast.force_max, fast.stiffness, slow.force_max, slow.stiffness));
  RateCheck c;
  c.force_max_change = slow.force_max / fast.force_max - 1.0;
  c.stiffness_change = slow.stiffness / fast.stiffness - 1.0;
  if (fast.deflection_at_peak > 0) c.deflection_change = slow.deflection_at_peak / fast.deflection_at_peak - 1.0;
  c.force_max_ok = std::abs(c.force_max_change) < criteria.force_max;
  c.stiffness_ok = std::abs(c.stiffness_change) < criteria.stiffness;
  c.both_failed = fast.failed && slow.failed;
  return c;
}

std::string format_rate_check(const CurveAnalysis& fast, const CurveAnalysis& slow, double fast_speed,
                              double slow_speed, const RateCheck& c, const RateCheckCriteria& criteria) {
  auto row = [](const char* name, double speed, const CurveAnalysis& a) {
    return fmt::format("  {:<5} {:8.4g} mm/s  F_max = {:8.5g} N  k = {:8.5g} N/mm (R^2 {:.4f})  E = {:7.4g} MPa  "
                       "w_s,max = {:6.4f} mm  {}\n",
                       name, 1e3 * speed, a.force_max, 1e-3 * a.stiffness, a.fit.r_squared, 1e-6 * a.youngs_modulus,
                       1e3 * a.deflection_at_peak, a.failed ? "failed" : "did NOT fail");
  };
  std::string s = "quasi-static check: the same packing at the scene's loading rate and at the reduced rate\n";
  s += row("rate", fast_speed, fast);
  s += row("slow", slow_speed, slow);
  s += fmt::format("  F_max changed {:+.2f} % (criterion |change| < {:.1f} %): {}\n", 100 * c.force_max_change,
                   100 * criteria.force_max, c.force_max_ok ? "pass" : "FAIL");
  s += fmt::format("  stiffness changed {:+.2f} % (criterion |change| < {:.1f} %): {}\n", 100 * c.stiffness_change,
                   100 * criteria.stiffness, c.stiffness_ok ? "pass" : "FAIL");
  s += fmt::format("  w_s,max changed {:+.2f} % (reported only)\n", 100 * c.deflection_change);
  if (!c.both_failed) s += "  FAIL: a run did not break, so its F_max is not a strength\n";
  s += fmt::format("  quasi-static at this rate: {}\n", c.passed() ? "yes" : "NO");
  return s;
}

}  // namespace shard::bending
