#pragma once
// Sub-commands of `shard` register themselves on the CLI11 app. Each sets a callback that stores
// its exit code in the context; errors propagate as exceptions and main prints them.
#include <filesystem>
#include <vector>

namespace CLI {
class App;
}

namespace shard {

struct CommandContext {
  std::vector<std::filesystem::path> plugin_dirs;  // --plugin-dir, before the sub-command
  int exit_code = 0;
};

void add_run_command(CLI::App& app, CommandContext& ctx);
void add_plugins_command(CLI::App& app, CommandContext& ctx);
void add_schema_command(CLI::App& app, CommandContext& ctx);  // the scene reference in Markdown
void add_check_command(CLI::App& app, CommandContext& ctx);  // check: a scene validated, not run
void add_bending_command(CLI::App& app, CommandContext& ctx);  // bending, calibrate
void add_fragments_command(CLI::App& app, CommandContext& ctx);
void add_measure_command(CLI::App& app, CommandContext& ctx);  // compare, synth, diagnose
void add_new_plugin_command(CLI::App& app, CommandContext& ctx);
void add_sweep_command(CLI::App& app, CommandContext& ctx);  // sweep: many runs, pooled plate statistics
void add_run_worker_command(CLI::App& app, CommandContext& ctx);  // hidden: one isolated run

}  // namespace shard
