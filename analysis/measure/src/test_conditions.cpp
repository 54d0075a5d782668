#include "shard/measure/test_conditions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace shard::measure {

bool is_ramp_name(const std::string& name) { return name == "1-cos" || name == "linear" || name == "none"; }

Curve zeroed_at_preload(const Curve& curve, double preload, const std::string& what) {
  std::size_t k = 0;
  while (k < curve.size() && !(curve.force[k] >= preload)) ++k;
  if (k == curve.size()) {
    const double peak = curve.size() ? *std::max_element(curve.force.begin(), curve.force.end()) : 0.0;
    throw std::runtime_error(fmt::format("{}: the force never reaches the seating preload {:g} N (its largest is {:.4g} "
                                         "N), so the curve has no zero; lower seating_preload in metadata.toml's [test]",
                                         what, preload, peak));
  }
  // Where the force crosses the preload between samples k - 1 and k (k = 0: the first sample).
  const double f = k == 0 ? 1.0 : (preload - curve.force[k - 1]) / (curve.force[k] - curve.force[k - 1]);
  const auto at = [&](const std::vector<double>& v) { return k == 0 ? v[0] : v[k - 1] + f * (v[k] - v[k - 1]); };
  const double t0 = at(curve.time), d0 = at(curve.displacement);
  Curve out;
  out.id = curve.id;
  const bool uncertain = curve.u_force.size() == curve.size() && curve.u_displacement.size() == curve.size();
  auto push = [&](double t, double d, double force, std::size_t u) {
    out.time.push_back(t - t0);
    out.displacement.push_back(d - d0);
    out.force.push_back(force);
    if (uncertain) {
      out.u_displacement.push_back(curve.u_displacement[u]);
      out.u_force.push_back(curve.u_force[u]);
    }
  };
  if (k > 0 && f < 1.0) push(t0, d0, preload, k);  // the zero itself, unless a sample lies on it
  for (std::size_t i = k; i < curve.size(); ++i) push(curve.time[i], curve.displacement[i], curve.force[i], i);
  return out;
}

}  // namespace shard::measure
