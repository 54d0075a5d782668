#pragma once
// One row per plate (parent body) of one or many runs: what its first wall contact was and what
// became of it, with its fragments' sizes and masses kept so that plates can be pooled and
// resampled (breakage_curve.hpp). `shard fragments --by-body --report` and `shard sweep` both
// build their rows here from the same per-body statistics, so their numbers agree bit for bit.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shard/analysis/body_statistics.hpp"
#include "shard/analysis/fragment_table.hpp"
#include "shard/run_file.hpp"

namespace shard::analysis {

struct PlateOutcome {
  std::string run;              // the run's label (a sweep: value and seed; else the run file)
  double value = 0;             // the varied scene value of a sweep's run (0 for a single run)
  std::int64_t seed = 0;        // the sweep's seed index of the run
  std::int32_t body = 0;
  bool impacted = false;        // touched a wall during the run (/body_impacts)
  double impact_speed = 0;      // m/s, centre-of-mass speed at the first wall contact
  double impact_angle = 0;      // degrees from the wall's inward normal
  bool broken = false;
  std::size_t fragments = 0;
  double mass = 0;              // kg
  double largest_fraction = 0;
  double x10 = 0, x50 = 0, x90 = 0;  // m, of its own fragments (mass-weighted d_eq)
  double fines_mass = 0;        // kg
  std::vector<double> fragment_d, fragment_mass;  // m, kg: every fragment whose parent it is
};

// The plates of one analysed frame: one row per body of `report`, with the fragments of
// `fragments` whose parent body (Fragment::body) it is.
std::vector<PlateOutcome> plate_outcomes(const BodyReport& report, const std::vector<Fragment>& fragments,
                                         const std::string& run, double value = 0, std::int64_t seed = 0);

// The per-body analysis of one run file as `shard fragments --by-body` makes it: the fragments of
// `frame` (default the last), body_statistics with `intact_fraction` and `fines_size`, and the
// first wall contacts of /body_impacts.
struct RunBodies {
  std::int64_t frame = 0;
  double time = 0;  // s, of the frame
  std::vector<Fragment> fragments;
  BodyReport report;
};
RunBodies analyse_run_bodies(const RunFile& file, std::optional<std::int64_t> frame, double intact_fraction,
                             double fines_size, std::optional<double> density = std::nullopt);

}  // namespace shard::analysis
