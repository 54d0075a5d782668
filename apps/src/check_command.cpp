// `shard check SCENE`: everything `shard run` checks before its first step -- every key, the
// plugins and their parameters, the files the scene names (geometry, motion tables), the bodies
// generated and the time step -- without running a step or writing a file.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "shard/app/commands.hpp"
#include "shard/app/run_command.hpp"
#include "shard/driver/time_step_report.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

namespace shard {
namespace {

struct CheckOptions {
  std::filesystem::path scene;
  std::vector<std::string> overrides;
};

std::string plugin_line(const PluginHost& host, PluginKind kind, const PluginChoice& choice) {
  const LoadedPlugin& p = host.find(kind, choice.name);
  return fmt::format("  {} {} {} ({})", to_string(kind), p.info.name, p.info.version, p.file);
}

void print_plugins(const Scene& scene, const PluginHost& host) {
  for (const auto& body : scene.bodies)
    fmt::print("{}{}\n", plugin_line(host, PluginKind::Generator, body.generator),
               body.from_generator_section ? "" : " for body " + body.name);
  if (scene.contact) fmt::print("{}\n", plugin_line(host, PluginKind::Contact, *scene.contact));
  if (scene.bond) {
    fmt::print("{}\n", plugin_line(host, PluginKind::Bond, *scene.bond));
    for (const auto* e : host.bond_effects_on(scene.bond->name, scene.bond->params))
      fmt::print("  bond_effect {} {} ({})\n", e->info.name, e->info.version, e->file);
  }
}

void print_setup(const Scene& scene, const SceneInstance& inst) {
  std::string walls;
  for (const auto& w : scene.walls) walls += (walls.empty() ? "" : ", ") + w.name;
  fmt::print("  {} bodies, {} particles, {} bonds; {} walls{}\n", inst.body_names.size(), inst.body.radius.size(),
             inst.body.bonds.size(), scene.walls.size(), walls.empty() ? "" : " (" + walls + ")");
  const driver::TimeStepReport time_step = driver::time_step_report(scene, *inst.simulation);
  for (const auto& limit : time_step.limits) fmt::print("  {}\n", limit.second);
  fmt::print("  {}\n", time_step.chosen);
}

int check_scene(const CheckOptions& o, const CommandContext& ctx) {
  PluginHost host;
  load_plugins(host, ctx.plugin_dirs, std::cerr);
  const Scene scene = load_scene(o.scene, host, parse_overrides(o.overrides));
  fmt::print("{}: keys and plugin parameters valid\n", o.scene.string());
  print_plugins(scene, host);
  // Generating the bodies reads the geometry files and checks the packing; building the
  // simulation reads the walls' meshes and tables and computes the time step.
  const SceneInstance inst = instantiate(scene, host, [](const std::string& line) { fmt::print("  {}\n", line); });
  print_setup(scene, inst);
  fmt::print("{}: ready to run (nothing was run or written)\n", o.scene.string());
  return 0;
}

}  // namespace

void add_check_command(CLI::App& app, CommandContext& ctx) {
  auto o = std::make_shared<CheckOptions>();
  auto* cmd = app.add_subcommand("check", "validate a scene without running it: keys, plugins, the files it names, "
                                          "the bodies and the time step; exits non-zero with the first error");
  cmd->add_option("scene", o->scene, "scene .toml")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", o->overrides, "override a scene key as `shard run --set` does, e.g. --set bond.youngs_modulus=13e6");
  cmd->callback([o, &ctx] { ctx.exit_code = check_scene(*o, ctx); });
}

}  // namespace shard
