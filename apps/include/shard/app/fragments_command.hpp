#pragma once
// `shard fragments run.h5 [--frame K] [--csv out.csv] [--plot fsd.png] [--write-labels]
//                         [--fines D] [--density RHO] [--since K0] [--rows N]
//                         [--by-body [--intact-fraction F] [--body-csv bodies.csv]
//                                    [--report DIR [--speed-bins N | --speed-edges V1,V2,...]]]`
// Labels the fragments of one frame (default: the last), prints their table and the size
// distribution, and optionally writes the CSV, the plot, and the labels back into the run file.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace shard {

struct FragmentsOptions {
  std::filesystem::path run_file;
  std::optional<std::int64_t> frame;           // /frames/<k:06d>; default the last frame
  std::optional<std::filesystem::path> csv;    // one row per fragment, every column
  std::optional<std::filesystem::path> plot;   // .png or .svg, drawn by gnuplot
  bool write_labels = false;   // "fragment" dataset in the frame + /fragments/<k:06d> table
  double fines_size = 0;       // m; mass of fragments with d_eq below it is reported
  std::optional<double> density;               // kg/m^3, when the file has no masses
  std::optional<std::int64_t> since;           // earlier frame: print the lineage since it
  std::size_t rows = 20;       // table rows printed (all are in the CSV)
  // Per parent body: broken or not, fragments, x10/x50/x90, fines; the run's breakage
  // probability and pooled distribution. Written to /bodies/<k:06d> of the run file.
  bool by_body = false;
  double intact_fraction = 0.9;  // a body is broken when its largest fragment holds less of its mass
  std::optional<std::filesystem::path> body_csv;  // the per-body table as CSV
  // Breakage versus impact speed (process_report.hpp): tables, picture and report.md in this folder.
  std::optional<std::filesystem::path> report;
  std::size_t speed_bins = 0;          // equal-width bins; 0: round(sqrt(plates))
  std::vector<double> speed_edges;     // m/s, explicit bin edges instead
  std::string command_line;            // for the report page
};

// Returns 0 on success, 1 on an error (reported on err as one line starting "error: ").
int fragments_command(const FragmentsOptions& options, std::ostream& out, std::ostream& err);

}  // namespace shard
