// The `shard` command line: each sub-command lives in its own *_command.cpp and registers here.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <optional>
#include <string>
#include <vector>

#include "shard/app/command_routing.hpp"
#include "shard/app/commands.hpp"
#include "shard/hdf5_quiet.hpp"
#include "shard/version.hpp"
#if SHARD_MPI_ENSEMBLE
#include "run_job.hpp"
#include "shard/app/run_ensemble.hpp"
#include "shard/driver/rank_runs.hpp"
#endif

int main(int argc, char** argv) {
  // Before HDF5's first use, which the guard below is: see run_scene (run_command.cpp).
  H5dont_atexit();
  // No HDF5 error stack reaches the terminal: every failure is reported as one line below.
  const shard::QuietHdf5Errors quiet_hdf5;
  CLI::App app{"Shard: bonded-particle DEM for the breakage of complex-shaped bodies"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "shard " + shard::version_line());
  shard::CommandContext ctx;
  app.add_option("--plugin-dir", ctx.plugin_dirs, "extra folder to search for plugins (repeatable)")
      ->check(CLI::ExistingDirectory);
  shard::add_run_command(app, ctx);
  shard::add_check_command(app, ctx);
  shard::add_plugins_command(app, ctx);
  shard::add_schema_command(app, ctx);
  shard::add_bending_command(app, ctx);  // bending, calibrate
  shard::add_fragments_command(app, ctx);
  shard::add_measure_command(app, ctx);
  shard::add_new_plugin_command(app, ctx);
  shard::add_sweep_command(app, ctx);
  shard::add_run_worker_command(app, ctx);
  std::vector<std::string> args(argv, argv + argc);
  if (const auto help = shard::forms_help(app, args)) {
    fmt::print("{}", *help);
    return 0;
  }
  shard::route_measurement_command(args);
#if SHARD_MPI_ENSEMBLE
  // Under mpirun a measurement command's runs spread over the ranks: rank 0 runs the command, the
  // others run its simulations until it ends (docs/how-to/run-on-a-cluster.md, "A measurement ensemble
  // over ranks").
  std::optional<shard::driver::RankEnsemble> ensemble;
  if (shard::spreads_runs_over_ranks(args)) {
    ensemble.emplace(argc, argv);
    if (ensemble->rank() > 0) return ensemble->serve(shard::run_encoded_job);
  }
#endif
  std::vector<char*> words;
  for (auto& a : args) words.push_back(a.data());
  try {
    app.parse(static_cast<int>(words.size()), words.data());
  } catch (const CLI::ParseError& e) {
    // --help and --version arrive as ParseErrors with exit code 0: CLI11 prints them.
    if (e.get_exit_code() == 0) return app.exit(e);
    // A bad option or value is a one-line error like every other (docs/reference/errors.md).
    fmt::print(stderr, "shard: error: {}; `shard --help` lists the commands, `shard COMMAND --help` their options\n",
               e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "shard: error: {}\n", e.what());
    return 1;
  }
  return ctx.exit_code;
}
