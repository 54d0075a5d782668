#pragma once
// How the lab ran and recorded its tests, as metadata.toml's [test] table states it
// (docs/how-to/bring-lab-data.md): the seating preload at which a curve's displacement is zeroed, the
// load cell's known zero offset, the pins' acceleration ramp, the material's grain size and the
// smallest fragment counted. The model is run and its curves recorded the same way.
#include <string>

#include "shard/measure/curve.hpp"

namespace shard::measure {

struct TestConditions {
  double seating_preload = 0;  // N; > 0: a curve starts (t = 0, d = 0) where the force first reached it
  double zero_offset = 0;      // N, what the load cell reads at zero load; subtracted from every force read
  std::string ramp;            // the pins' "1-cos", "linear" or "none" ramp; empty: not recorded
  double ramp_time = 0;        // s, the pins' time to reach the loading rate
  double grain_size = 0;       // m, mean grain (primary particle) diameter; 0: not recorded
  double fragment_size_threshold = 0;  // m, fragments smaller than this were not counted; 0: all were
  std::string notes;                   // free text about the test

  bool has_ramp() const { return !ramp.empty() && ramp != "none"; }
};

// The ramp names the kernel's [[wall]] ramp takes (kernel/include/shard/wall_motion.hpp).
bool is_ramp_name(const std::string& name);

// The curve as a lab with seating preload `preload` records it: time and displacement zeroed
// where the force first reaches `preload` (linear interpolation between the samples around it),
// the samples before dropped. Throws std::runtime_error naming `what` when the force never
// reaches the preload.
Curve zeroed_at_preload(const Curve& curve, double preload, const std::string& what);

}  // namespace shard::measure
