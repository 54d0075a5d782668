#pragma once
// Synthetic measurements (`shard synth`): a simulated "truth" curve turned into what a testing
// machine would record. Each effect is physical, with its neutral value = off:
//   specimen scatter   force scaled by 1 + N(0, scatter) per specimen (strength and stiffness
//                      vary together between specimens of one batch), 1
//   machine compliance the pins' recorded displacement includes the load frame's spring in
//                      series with the specimen: w_rec = w + C F, C in m/N
//   load-cell offset   constant per specimen, N(0, offset) N (a tare error)
//   load-cell noise    independent per reading, N(0, force_noise) N
//   quantisation       displacement rounded to multiples of `displacement_step` m
//   seating closure    rough specimen faces under the pins and rollers: the asperities close
//                      as the load builds, a hyperbolic closure law (Bandis et al. 1983, rock
//                      joints; the "toe" ASTM D790 compensates) in series with the specimen:
//                      w_rec = w + g F / (F + F_h), g the closure gap in m, F_h the force at half
//                      closure in N. Not in the effect library: the test of "unexplained".
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "shard/measure/curve.hpp"
#include "shard/measure/measurements.hpp"

namespace shard::measure {

struct SensorModel {
  double specimen_scatter = 0;    // 1, relative standard deviation of the force scale
  double machine_compliance = 0;  // m/N
  double force_offset = 0;        // N, standard deviation of the per-specimen tare
  double force_noise = 0;         // N, per reading
  double displacement_step = 0;   // m, resolution of the displacement transducer
  double seating_gap = 0;         // m, closure gap g of rough specimen faces
  double seating_half_force = 0;  // N, force F_h at which half the gap has closed (> 0 with a gap)
};

// The recorded curve; u_force and u_displacement are the standard uncertainties the sensor model
// implies (noise and offset for the force, step / sqrt(12) for a quantised displacement).
Curve record(const Curve& truth, const SensorModel& sensor, std::mt19937_64& rng);

// Series-spring correction of a simulated curve for a compliant machine: w + C F.
Curve with_machine_compliance(const Curve& c, double compliance);

// The lab a synthetic set is recorded by: its sensor, how it runs and records a test, its name.
struct SyntheticLab {
  std::string name;
  SensorModel sensor;
  TestConditions test;  // seating_preload zeroes each recorded curve there; zero_offset is added
  std::uint64_t noise_seed = 1;
};

// The measurement set such a lab writes of the truth's simulated specimens (`truth[k]` at
// `rates[k]`): each curve recorded through the sensor, zeroed at the preload, offset as the load
// cell reads; crack position and fragments as noted after the test; the specimens' dimensions
// those of `geometry`. Ids get a _rate<r> suffix when there are several rates.
MeasurementSet synthetic_set(const std::vector<std::vector<Specimen>>& truth, const std::vector<double>& rates,
                             const Specimen& geometry, const SyntheticLab& lab);

}  // namespace shard::measure
