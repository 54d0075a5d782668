#pragma once
// The measurement sub-commands registered by add_measure_command (commands.hpp).
namespace CLI {
class App;
}

namespace shard {

struct CommandContext;

void add_diagnose_command(CLI::App& app, CommandContext& ctx);          // measure_diagnose.cpp
void add_calibrate_effect_command(CLI::App& app, CommandContext& ctx);  // measure_calibrate.cpp
void add_history_command(CLI::App& app, CommandContext& ctx);           // measure_history.cpp
void add_diagnose_sets_command(CLI::App& app, CommandContext& ctx);     // measure_contrast.cpp
void add_calibrate_contrast_command(CLI::App& app, CommandContext& ctx);  // measure_contrast_calibrate.cpp

}  // namespace shard
