// `shard fragments run.h5`: fragment table, size distribution and lineage of a frame.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "shard/analysis/fragments_cli.hpp"
#include "shard/analysis/fragments_command.hpp"
#include "shard/app/commands.hpp"

namespace shard {

void add_fragments_command(CLI::App& app, CommandContext& ctx) {
  auto options = std::make_shared<analysis::FragmentsOptions>();
  auto* cmd = app.add_subcommand("fragments", "fragments of a frame: table, size distribution, lineage");
  analysis::add_fragments_options(*cmd, *options);
  cmd->callback([options, &ctx] { ctx.exit_code = analysis::fragments_command(*options, std::cout, std::cerr); });
}

}  // namespace shard
