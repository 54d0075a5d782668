// `shard run` and `shard plugins`.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <csignal>

#include <iostream>
#include <memory>

#include "option_checks.hpp"
#include "param_text.hpp"
#include "shard/app/commands.hpp"
#include "shard/app/run_command.hpp"
#include "shard/plugin_host.hpp"

namespace shard {

void add_run_command(CLI::App& app, CommandContext& ctx) {
  auto options = std::make_shared<RunOptions>();
  auto assignments = std::make_shared<std::vector<std::string>>();
  auto* cmd = app.add_subcommand("run", "run a scene file");
  cmd->add_option("scene", options->scene, "scene .toml (not with --restart)");
  cmd->add_option("--restart", options->restart, "continue run.h5 from its checkpoint run.checkpoint.h5");
  cmd->add_option("--checkpoint-every", options->checkpoint_every, "frames between checkpoints (0: only when stopping)")
      ->check(number_from(0, false, "0 (checkpoint only when stopping) or a number of frames"));
  cmd->add_option("--set", *assignments,
                  "override a scene key, e.g. --set bond.youngs_modulus=13e6 (with --restart: simulation.duration and "
                  "[stop] keys only, e.g. to run on past the end)");
  cmd->add_option("--out", options->out_dir, "output folder");
  cmd->add_option("--threads", options->threads, "OpenMP threads (default: all cores)")->check(thread_count());
  cmd->add_flag("--quiet", options->quiet, "no progress line");
  cmd->callback([options, assignments, &ctx] {
    options->plugin_dirs = ctx.plugin_dirs;
    options->overrides = parse_overrides(*assignments);
    options->decompose_under_mpirun = true;
    if (options->scene.empty() == options->restart.empty())
      throw std::invalid_argument("shard run needs a scene file, or --restart run.h5 (not both)");
    const RunSummary summary = run_scene(*options, std::cerr);
    // 128 + the signal, what a shell reports for a job it stopped: 130 for Ctrl-C (SIGINT), 143
    // for SIGTERM. A rank stopped because another rank was signalled reports SIGINT's.
    ctx.exit_code = summary.interrupted() ? 128 + (summary.interrupt_signal ? summary.interrupt_signal : SIGINT) : 0;
  });
}

void add_plugins_command(CLI::App& app, CommandContext& ctx) {
  auto* cmd = app.add_subcommand("plugins", "list the plugins found, with their parameters");
  cmd->callback([&ctx] {
    PluginHost host;
    load_plugins(host, ctx.plugin_dirs, std::cerr);
    for (const auto* p : host.plugins()) {
      fmt::print("{}/{} {}  ({})\n  {}\n", to_string(p->info.kind), p->info.name, p->info.version, p->file,
                 p->info.doc);
      for (const auto& s : p->info.params)
        fmt::print("    {:<26} {:<7} [{}] default {}{}{}  {}\n", s.name, param_type_text(s.type), s.unit,
                   param_default_text(s), s.neutral ? fmt::format(", neutral {}", *s.neutral) : "",
                   s.scope == ParamScope::Model ? "" : ", " + param_scope_text(s.scope), s.doc);
    }
    ctx.exit_code = 0;
  });
}

}  // namespace shard
