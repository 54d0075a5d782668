#pragma once
// `shard sweep SCENE --vary KEY=V1,V2,... [--seeds N] [--workers W] [--out DIR]`: every (value,
// seed) run of a scene, in parallel and in-process through the run pool (run_in_parallel), then
// all plates of all runs pooled: breakage probability and x50 against impact speed and against
// the varied value, with 95 % bands (Wilson for the share, bootstrap for x50), as CSV, HDF5, PNG
// and a report page (docs/how-to/parameter-sweep.md).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "shard/analysis/breakage_curve.hpp"
#include "shard/analysis/plate_outcome.hpp"

namespace shard {

struct SweepOptions {
  std::filesystem::path scene;
  std::string vary;                     // KEY=V1,V2,... (sweep_plan.hpp)
  std::vector<std::string> sets;        // --set section.key=value, applied to every run before the value
  int seeds = 1;                        // seed indices 0 .. seeds-1; 0 is the scene as written
  int workers = 0;                      // runs at once (one OpenMP thread each); 0: the cores
  std::filesystem::path out = "sweep";
  std::vector<std::filesystem::path> plugin_dirs;
  double intact_fraction = 0.9;         // as shard fragments --by-body
  double fines_size = 0;                // m
  std::size_t speed_bins = 0;           // 0: round(sqrt(impacted plates))
  std::vector<double> speed_edges;      // m/s, instead of speed_bins
  bool quiet = false;                   // no progress lines
  std::string command_line;             // for the report page
};

struct SweepRun {
  double value = 0;
  std::int64_t seed = 0;
  std::string label;                    // "v1.5_s0": the folder under DIR/runs
  std::filesystem::path run_file;
  std::string error;                    // why it failed; empty: it ran
  double wall_seconds = 0;
  std::size_t plates = 0, broken = 0;
  double x50 = 0;                       // m, all its fragments pooled
  bool failed() const { return !error.empty(); }
};

struct SweepResult {
  std::string value_label;              // what the value is, e.g. "|body.shard.velocity| along [0, 0, -1]"
  std::vector<SweepRun> runs;           // value-major, then seed
  std::vector<analysis::PlateOutcome> plates;  // of the runs that ran, in run order
  std::vector<analysis::BreakageGroup> by_value, by_speed;
  std::vector<double> speed_edges;
  double wall_seconds = 0;
  std::size_t failed() const;
};

// Runs the sweep and writes DIR/runs/<label>/run.h5 (+ /bodies/<k> in each, as `shard fragments
// --by-body`), DIR/plates.csv, runs.csv, breakage_vs_speed.csv, breakage_vs_value.csv, sweep.h5,
// the two PNGs and DIR/report.md. Progress lines go to `log`. Bad input (scene, key, values,
// options) throws before any run; a run that fails is reported in the result and the others go on.
SweepResult run_sweep(const SweepOptions& options, std::ostream& log);

}  // namespace shard
