// `shard run-worker`: one run of the measurement loop in a process of its own (run_job.hpp). Not
// for users: the run pool starts it with the job on its standard input and reads the outcome from
// its standard output, so a crash in a plugin ends this process and not the loop.
#include <CLI/CLI.hpp>

#include "run_job.hpp"
#include "shard/app/commands.hpp"

namespace shard {

void add_run_worker_command(CLI::App& app, CommandContext& ctx) {
  auto* cmd = app.add_subcommand("run-worker", "one run of the measurement loop, job on stdin (internal)");
  cmd->group("");  // hidden from --help
  cmd->callback([&ctx] { ctx.exit_code = serve_run_job(ctx.plugin_dirs); });
}

}  // namespace shard
