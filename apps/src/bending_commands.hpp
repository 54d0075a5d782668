#pragma once
// The bending sub-commands besides `bending` and `calibrate`, registered by add_bending_command.
namespace CLI {
class App;
}

namespace shard {
struct CommandContext;
void add_bending_rate_check_command(CLI::App& app, CommandContext& ctx);  // bending-rate-check
}  // namespace shard
