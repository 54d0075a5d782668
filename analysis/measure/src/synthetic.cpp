#include "shard/measure/synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shard::measure {

Curve with_machine_compliance(const Curve& c, double compliance) {
  Curve out = c;
  for (std::size_t k = 0; k < c.size(); ++k) out.displacement[k] = c.displacement[k] + compliance * c.force[k];
  return out;
}

Curve record(const Curve& truth, const SensorModel& s, std::mt19937_64& rng) {
  if (s.specimen_scatter < 0 || s.machine_compliance < 0 || s.force_offset < 0 || s.force_noise < 0 ||
      s.displacement_step < 0 || s.seating_gap < 0 || s.seating_half_force < 0)
    throw std::invalid_argument("sensor model: every setting is a size and must be >= 0");
  if (s.seating_gap > 0 && !(s.seating_half_force > 0))
    throw std::invalid_argument("sensor model: a seating gap needs the force at half closure (> 0 N)");
  std::normal_distribution<double> gauss(0, 1);
  const double scale = 1 + s.specimen_scatter * gauss(rng);
  const double offset = s.force_offset * gauss(rng);
  Curve scaled = truth;
  for (auto& f : scaled.force) f *= scale;
  Curve c = with_machine_compliance(scaled, s.machine_compliance);
  if (s.seating_gap > 0)
    for (std::size_t k = 0; k < c.size(); ++k) {
      const double f = std::max(scaled.force[k], 0.0);  // asperities open again, never pull
      c.displacement[k] += s.seating_gap * f / (f + s.seating_half_force);
    }
  const double u_f = std::hypot(s.force_noise, s.force_offset);
  const double u_w = s.displacement_step / std::sqrt(12.0);
  for (std::size_t k = 0; k < c.size(); ++k) {
    // The frame deflects under the true force; the load cell then adds its tare and noise.
    c.force[k] += offset + s.force_noise * gauss(rng);
    if (s.displacement_step > 0) c.displacement[k] = s.displacement_step * std::round(c.displacement[k] / s.displacement_step);
  }
  c.u_force.assign(c.size(), u_f > 0 ? u_f : 1e-12);
  c.u_displacement.assign(c.size(), u_w);
  return c;
}

}  // namespace shard::measure
