// The `shard` command line.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>

#include "shard/app/run_command.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

namespace {

std::string param_type(shard::ParamType t) {
  switch (t) {
    case shard::ParamType::Number: return "number";
    case shard::ParamType::Integer: return "integer";
    case shard::ParamType::Boolean: return "bool";
    case shard::ParamType::String: return "string";
    case shard::ParamType::Vector3: return "vec3";
  }
  return "?";
}

std::string default_text(const shard::ParamSpec& s) {
  return std::visit(
      [](const auto& d) -> std::string {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, std::monostate>) return "(required)";
        else if constexpr (std::is_same_v<T, double>) return fmt::format("{}", d);
        else if constexpr (std::is_same_v<T, bool>) return d ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>) return "\"" + d + "\"";
        else return fmt::format("[{}, {}, {}]", d[0], d[1], d[2]);
      },
      s.default_value);
}

int plugins_command(const std::vector<std::filesystem::path>& dirs) {
  shard::PluginHost host;
  shard::load_plugins(host, dirs, std::cerr);
  for (const auto* p : host.plugins()) {
    fmt::print("{}/{} {}  ({})\n  {}\n", shard::to_string(p->info.kind), p->info.name, p->info.version, p->file,
               p->info.doc);
    for (const auto& s : p->info.params)
      fmt::print("    {:<22} {:<7} [{}] default {}{}  {}\n", s.name, param_type(s.type), s.unit, default_text(s),
                 s.neutral ? fmt::format(", neutral {}", *s.neutral) : "", s.doc);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Shard: bonded-particle DEM for the breakage of complex-shaped bodies"};
  app.require_subcommand(1);
  std::vector<std::filesystem::path> plugin_dirs;
  app.add_option("--plugin-dir", plugin_dirs, "extra folder to search for plugins (repeatable)");

  shard::RunOptions run;
  auto* run_cmd = app.add_subcommand("run", "run a scene file");
  run_cmd->add_option("scene", run.scene, "scene .toml")->required();
  run_cmd->add_option("--set", run.overrides, "override a scene key, e.g. --set bond.youngs_modulus=13e6");
  run_cmd->add_option("--out", run.out_dir, "output folder");
  run_cmd->add_option("--threads", run.threads, "OpenMP threads (default: all cores)");
  run_cmd->add_flag("--quiet", run.quiet, "no progress line");

  auto* plugins_cmd = app.add_subcommand("plugins", "list the plugins found, with their parameters");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*run_cmd) {
      run.plugin_dirs = plugin_dirs;
      shard::run_scene(run, std::cerr);
      return 0;
    }
    if (*plugins_cmd) return plugins_command(plugin_dirs);
  } catch (const std::exception& e) {
    fmt::print(stderr, "shard: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
