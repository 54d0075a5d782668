// `shard fragments run.h5`: fragment table, size distribution and lineage of a frame.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "shard/app/commands.hpp"
#include "shard/app/fragments_cli.hpp"
#include "shard/app/fragments_command.hpp"

namespace shard {

void add_fragments_command(CLI::App& app, CommandContext& ctx) {
  auto options = std::make_shared<FragmentsOptions>();
  auto* cmd = app.add_subcommand("fragments", "fragments of a frame: table, size distribution, lineage");
  add_fragments_options(*cmd, *options);
  cmd->callback([options, &ctx] { ctx.exit_code = fragments_command(*options, std::cout, std::cerr); });
}

}  // namespace shard
