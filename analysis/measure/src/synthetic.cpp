#include "shard/measure/synthetic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shard/measure/test_conditions.hpp"

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

MeasurementSet synthetic_set(const std::vector<std::vector<Specimen>>& truth, const std::vector<double>& rates,
                             const Specimen& geometry, const SyntheticLab& lab) {
  MeasurementSet set;
  set.metadata.name = lab.name;
  set.metadata.test = lab.test;
  set.metadata.load_cell_uncertainty = std::max(std::hypot(lab.sensor.force_noise, lab.sensor.force_offset), 1e-12);
  set.metadata.displacement_uncertainty = lab.sensor.displacement_step / std::sqrt(12.0);
  std::mt19937_64 rng(lab.noise_seed);
  for (std::size_t k = 0; k < truth.size(); ++k)
    for (const auto& sim : truth[k]) {
      Specimen s = geometry;
      s.id = rates.size() > 1 ? fmt::format("{}_rate{:g}", sim.id, rates[k]) : sim.id;
      s.loading_rate = rates[k];
      s.curve = record(sim.curve, lab.sensor, rng);
      if (lab.test.seating_preload > 0)
        s.curve = zeroed_at_preload(s.curve, lab.test.seating_preload, fmt::format("synthetic specimen {}", s.id));
      for (double& f : s.curve.force) f += lab.test.zero_offset;  // what the load cell reads
      // What a lab notes after the test: where the crack is and the pieces (sieved sizes).
      s.crack_position = sim.crack_position;
      s.fragment_sizes = sim.fragment_sizes;
      s.fragment_count = sim.fragment_count;
      set.specimens.push_back(std::move(s));
    }
  return set;
}

}  // namespace shard::measure
