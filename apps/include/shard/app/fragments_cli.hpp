#pragma once
// Registers the options of `shard fragments` on a CLI11 (sub)command; header-only so a
// test parses the same options without the command table. Usage in apps/:
//   FragmentsOptions opts; auto* sub = app.add_subcommand("fragments", "...");
//   add_fragments_options(*sub, opts); sub->callback([&] { rc = fragments_command(opts, std::cout, std::cerr); });
#include <CLI/CLI.hpp>

#include "shard/app/fragments_command.hpp"

namespace shard {

inline void add_fragments_options(CLI::App& app, FragmentsOptions& o) {
  app.add_option("run_file", o.run_file, "run.h5 written by `shard run`")->required()->check(CLI::ExistingFile);
  app.add_option("--frame", o.frame, "frame number k of /frames/<k:06d> (default: the last)");
  app.add_option("--csv", o.csv, "write the fragment table (every fragment, every column) as CSV");
  app.add_option("--plot", o.plot, "draw the size distribution with gnuplot (.png or .svg)");
  app.add_flag("--write-labels", o.write_labels,
               "store the labels in the frame ('fragment' dataset) and the table under /fragments");
  app.add_option("--fines", o.fines_size, "fines size [m]: report the mass of fragments with d_eq below it")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--density", o.density, "particle density [kg/m^3] when the file has no masses")
      ->check(CLI::PositiveNumber);
  app.add_option("--since", o.since, "earlier frame: print which of its fragments became which");
  app.add_option("--rows", o.rows, "fragments listed in the printed table (default 20)");
  app.add_flag("--by-body", o.by_body,
               "statistics per parent body (broken, fragments, x10/x50/x90, fines) and the breakage probability; "
               "stored under /bodies/<k> of the run file");
  app.add_option("--intact-fraction", o.intact_fraction,
                 "with --by-body: a body is broken when its largest fragment holds less than this share of its mass "
                 "(default 0.9)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--body-csv", o.body_csv, "with --by-body: write the per-body table as CSV");
  app.add_option("--report", o.report,
                 "with --by-body: breakage probability and x50 versus impact speed (Wilson and bootstrap 95 % "
                 "intervals) as CSV, a gnuplot PNG and report.md in this folder, the table also under /breakage/<k>");
  app.add_option("--speed-bins", o.speed_bins, "with --report: equal-width impact speed bins (default round(sqrt(plates)))")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000}));
  app.add_option("--speed-edges", o.speed_edges, "with --report: impact speed bin edges [m/s], ascending, e.g. 0.5,1,1.5,2")
      ->delimiter(',')
      ->expected(2, 1000);
}

}  // namespace shard
