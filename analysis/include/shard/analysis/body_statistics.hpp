#pragma once
// Statistics per parent body of a many-body run (docs/reference/fragments.md, "Per body"): whether each
// body broke, into how many fragments, their mass-weighted size distribution, and the run's
// breakage probability and pooled distribution.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shard/analysis/fragment_table.hpp"
#include "shard/analysis/size_distribution.hpp"
#include "shard/body_impacts.hpp"

namespace shard::analysis {

struct BodyStatistics {
  std::int32_t body = 0;
  std::size_t particles = 0;
  double mass = 0;                // kg, of the body's particles
  std::size_t fragments = 0;      // fragments whose parent body (Fragment::body) is this one
  double largest_fraction = 0;    // mass of its largest fragment / mass
  bool broken = false;            // largest_fraction < intact_fraction
  SizeDistribution fsd;           // of its fragments (d_eq, mass-weighted)
  // The first wall contact, from the run's /body_impacts (absent: impacted false).
  bool impacted = false;
  double impact_time = 0;         // s
  double impact_speed = 0;        // m/s, centre-of-mass speed
  double impact_angle = 0;        // degrees between the velocity and the wall's inward normal
  std::int32_t impact_wall = -1;  // index in the scene's [[wall]] order
};

struct BodyReport {
  std::vector<BodyStatistics> bodies;  // ascending body id; ids without particles are left out
  std::size_t broken = 0;
  double breakage_probability = 0;     // broken / bodies
  double intact_fraction = 0;          // the threshold used
  SizeDistribution pooled;             // every fragment of every body
};

// `fragments` from fragment_table of the same sample. A body is broken when its largest fragment
// holds less than `intact_fraction` (in (0, 1]) of its mass; 1 means any fragment broken off.
BodyReport body_statistics(const ParticleSample& particles, const std::vector<Fragment>& fragments,
                           double intact_fraction, double fines_size);

// Copies each body's first wall contact (`impacts` indexed by body id, RunFile::read_body_impacts)
// into the report.
void attach_impacts(BodyReport& report, const std::vector<BodyImpact>& impacts);

}  // namespace shard::analysis
