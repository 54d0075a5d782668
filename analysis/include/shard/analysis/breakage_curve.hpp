#pragma once
// The plant engineer's curve: breakage probability and fragment size against impact speed (or
// against a scene value a sweep varied), with confidence bands, from plates pooled over runs.
//
// A group of plates (a bin of impact speed, or the runs of one swept value) gives
//   - broken share = broken / plates, with Wilson's 95 % score interval (binomial_interval.hpp);
//   - x10, x50, x90 of all its plates' fragments pooled (mass-weighted d_eq, the rule of
//     size_distribution.hpp): the product's size distribution;
//   - a 95 % interval of that x50 by the bootstrap percentile method: the plates are resampled
//     with replacement (a plate's fragments stay together, as they are not independent), the
//     pooled x50 recomputed per resample, and the 2.5 % and 97.5 % quantiles of the resampled
//     x50s taken (linear between order statistics). Resamples come from std::mt19937_64 with a
//     fixed seed, so the interval is the same on every machine and every run.
// Plates without a wall contact have no impact speed: they are left out of the speed bins and
// counted as `not_impacted` in a group by value (where they still count as plates).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shard/analysis/binomial_interval.hpp"
#include "shard/analysis/plate_outcome.hpp"

namespace shard::analysis {

struct CurveOptions {
  double z = kZ95;                // of the broken share's Wilson interval
  double level = 0.95;            // of the x50 bootstrap interval
  std::size_t resamples = 2000;   // bootstrap resamples
  std::uint64_t seed = 1;         // of the resampling sequence
};

struct BreakageGroup {
  double lower = 0, upper = 0;    // the bin's impact speeds [m/s], or the swept value twice
  std::size_t plates = 0, broken = 0, not_impacted = 0;
  double broken_share = 0;        // broken / plates (0 when empty)
  Interval broken_interval{0, 1};
  double mean_speed = 0, min_speed = 0, max_speed = 0;  // m/s, of the impacted plates (0 if none)
  std::size_t fragments = 0;
  double x10 = 0, x50 = 0, x90 = 0;  // m, pooled fragments (0 when empty)
  Interval x50_interval;          // m, bootstrap; [x50, x50] for a single plate
};

// Statistics of one group of plates.
BreakageGroup breakage_group(const std::vector<const PlateOutcome*>& plates, const CurveOptions& options = {});

// The bootstrap percentile interval of the pooled x50 of `plates` (see above).
Interval bootstrap_x50(const std::vector<const PlateOutcome*>& plates, const CurveOptions& options = {});

// `bins` equal-width bins spanning the impacted plates' speeds [min, max] (bins + 1 ascending
// edges). bins = 0 chooses round(sqrt(impacted plates)), between 1 and 12. One speed, or none,
// gives one bin around it.
std::vector<double> speed_bin_edges(const std::vector<PlateOutcome>& plates, std::size_t bins = 0);

// One group per bin [e_k, e_k+1) (the last bin closed) of the impacted plates; plates outside
// every bin are left out. Throws std::invalid_argument unless the edges ascend strictly.
std::vector<BreakageGroup> breakage_by_speed(const std::vector<PlateOutcome>& plates, const std::vector<double>& edges,
                                             const CurveOptions& options = {});

// One group per distinct PlateOutcome::value, ascending.
std::vector<BreakageGroup> breakage_by_value(const std::vector<PlateOutcome>& plates,
                                             const CurveOptions& options = {});

}  // namespace shard::analysis
