#pragma once
// Pieces of the process report (a markdown page): the breakage curve and the plates as markdown
// tables, the method paragraph, and the page of one run (`shard fragments --by-body --report`).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "shard/analysis/breakage_curve.hpp"
#include "shard/analysis/breakage_tables.hpp"
#include "shard/analysis/plate_outcome.hpp"
#include "shard/run_file.hpp"

namespace shard::analysis {

// | impact speed [m/s] (or value) | plates | broken | broken share [95 % interval] | ... | x50 [mm] [95 %] |
std::string markdown_group_table(const std::vector<BreakageGroup>& groups, GroupedBy by,
                                 const std::string& value_name = "value");
// One line per plate, the first `max_rows` (a last line says how many more are in the CSV).
std::string markdown_plate_table(const std::vector<PlateOutcome>& plates, std::size_t max_rows,
                                 const std::string& value_name = "");
// How broken, the share's interval and the x50 interval are defined.
std::string method_paragraph(const CurveOptions& options, double intact_fraction);
// Writes text to file; throws std::runtime_error when it cannot.
void write_text_file(const std::filesystem::path& file, const std::string& text);

struct RunReportOptions {
  std::filesystem::path dir;          // created when absent
  std::size_t speed_bins = 0;         // equal-width bins of impact speed; 0: round(sqrt(plates))
  std::vector<double> speed_edges;    // explicit bin edges [m/s] instead (ascending)
  CurveOptions curve;
  std::string command;                // the command line that made it, for the page
};

// The breakage report of one analysed run: DIR/plates.csv, DIR/breakage_vs_speed.csv,
// DIR/breakage_vs_speed.png (gnuplot), DIR/report.md, and the table by impact speed in the run
// file as /breakage/<k:06d>/by_impact_speed. Lines saying what was written go to `out`. A
// missing gnuplot leaves the picture out with a warning line on `out` (the tables are written).
void write_run_breakage_report(RunFile& file, const RunBodies& bodies, double intact_fraction,
                               const RunReportOptions& options, std::ostream& out);

}  // namespace shard::analysis
