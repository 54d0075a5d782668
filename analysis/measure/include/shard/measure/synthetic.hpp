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
#include <random>

#include "shard/measure/curve.hpp"

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

}  // namespace shard::measure
