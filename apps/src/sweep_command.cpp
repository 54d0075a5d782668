// `shard sweep SCENE --vary KEY=V1,V2,... [--seeds N] [--workers W] [--out DIR]`.
#include "shard/app/sweep_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "option_checks.hpp"
#include "shard/app/commands.hpp"

namespace shard {

void add_sweep_command(CLI::App& app, CommandContext& ctx) {
  auto o = std::make_shared<SweepOptions>();
  auto* cmd = app.add_subcommand(
      "sweep", "run a scene over a list of values of one key and several packing seeds, in parallel; breakage "
               "probability and x50 against impact speed and the value, with 95 % bands");
  cmd->add_option("scene", o->scene, "scene file (TOML)")->required();
  cmd->add_option("--vary", o->vary,
                  "KEY=V1,V2,...: a scene key as --set takes it and its values (SI units). A vector key (a velocity) "
                  "takes its magnitude, direction kept; KEY[i] one component (body.shard.stream.start[2]: drop height)")
      ->required();
  cmd->add_option("--seeds", o->seeds, "packing seeds per value (seed index s adds s to every seed; 0: the scene)")
      ->check(number_from(1, false, "at least 1"));
  cmd->add_option("--workers", o->workers, "runs at once, one thread each (default: the cores)")
      ->check(number_from(1, false, "at least 1 (leave --workers out to use every core)"));
  cmd->add_option("--out", o->out, "output folder (runs/, tables, pictures, report.md)");
  cmd->add_option("--set", o->sets, "section.key=value for every run (repeatable), before the varied value");
  cmd->add_option("--intact-fraction", o->intact_fraction,
                  "a plate is broken when its largest fragment holds less than this share of its mass (default 0.9)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--fines", o->fines_size, "fines size [m] of the per-plate tables")->check(CLI::NonNegativeNumber);
  cmd->add_option("--speed-bins", o->speed_bins, "equal-width impact speed bins (default round(sqrt(plates)))")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000}));
  cmd->add_option("--speed-edges", o->speed_edges, "impact speed bin edges [m/s], ascending, e.g. 0.5,1,1.5,2,2.5")
      ->delimiter(',')
      ->expected(2, 1000);
  cmd->add_flag("--quiet", o->quiet, "no progress lines");
  cmd->callback([o, &ctx] {
    o->plugin_dirs = ctx.plugin_dirs;
    o->command_line = fmt::format("shard sweep {} --vary {} --seeds {} --out {}", o->scene.string(), o->vary, o->seeds,
                                  o->out.string());
    for (const std::string& s : o->sets) o->command_line += fmt::format(" --set {}", s);
    const SweepResult r = run_sweep(*o, std::cerr);
    if (r.failed() > 0) {
      fmt::print(stderr, "shard: error: {} of {} runs failed (listed in {}/runs.csv and report.md); the statistics pool "
                         "the {} that ran\n",
                 r.failed(), r.runs.size(), o->out.string(), r.runs.size() - r.failed());
      ctx.exit_code = 1;
    }
  });
}

}  // namespace shard
