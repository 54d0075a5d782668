// `shard new-plugin KIND NAME [--dir DIR]`: writes a one-file plugin and its CMakeLists.txt from
// the templates, ready to build out of tree against the installed Shard package (docs/plugins.md).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/app/commands.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

struct NewPluginOptions {
  std::string kind;
  std::string name;
  fs::path dir;
  fs::path template_dir;
  bool force = false;
};

bool valid_name(const std::string& name) {
  if (name.empty() || !std::islower(static_cast<unsigned char>(name[0]))) return false;
  for (const char c : name)
    if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'))
      return false;
  return true;
}

// my_effect -> MyEffect
std::string class_name(const std::string& name) {
  std::string out;
  bool upper = true;
  for (const char c : name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}

// Installed: <prefix>/bin/shard -> <prefix>/share/shard/templates; in the build tree: the source.
std::vector<fs::path> template_search_path(const fs::path& explicit_dir) {
  std::vector<fs::path> dirs;
  if (!explicit_dir.empty()) dirs.push_back(explicit_dir);
  if (const char* env = std::getenv("SHARD_TEMPLATE_DIR")) dirs.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) dirs.push_back(exe.parent_path().parent_path() / "share" / "shard" / "templates");
#ifdef SHARD_SOURCE_TEMPLATE_DIR
  dirs.emplace_back(SHARD_SOURCE_TEMPLATE_DIR);
#endif
  return dirs;
}

std::string read_template(const std::vector<fs::path>& dirs, const std::string& file) {
  for (const auto& dir : dirs) {
    std::ifstream in(dir / file);
    if (!in) continue;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  std::string searched;
  for (const auto& dir : dirs) searched += "\n  " + dir.string();
  throw std::runtime_error(fmt::format("template {} not found; searched:{}\n(set SHARD_TEMPLATE_DIR)", file, searched));
}

std::string substitute(std::string text, const std::string& key, const std::string& value) {
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
    text.replace(at, key.size(), value);
  return text;
}

void write_file(const fs::path& file, const std::string& text, bool force) {
  if (fs::exists(file) && !force)
    throw std::runtime_error(fmt::format("{} exists; not overwritten (use --force)", file.string()));
  std::ofstream out(file);
  out << text;
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", file.string()));
}

void new_plugin(const NewPluginOptions& o, std::ostream& log) {
  if (o.kind != "contact" && o.kind != "bond" && o.kind != "generator")
    throw std::invalid_argument(fmt::format("unknown plugin kind '{}': contact, bond or generator", o.kind));
  if (!valid_name(o.name))
    throw std::invalid_argument(
        fmt::format("plugin name '{}': lower-case letters, digits and '_', starting with a letter", o.name));
  const fs::path dir = o.dir.empty() ? fs::path(o.name) : o.dir;
  const auto search = template_search_path(o.template_dir);
  auto fill = [&](std::string text) {
    text = substitute(std::move(text), "{{name}}", o.name);
    text = substitute(std::move(text), "{{class}}", class_name(o.name));
    return substitute(std::move(text), "{{kind}}", o.kind);
  };
  const std::string source = fill(read_template(search, o.kind + ".cpp.in"));
  const std::string lists = fill(read_template(search, "CMakeLists.txt.in"));
  fs::create_directories(dir);
  write_file(dir / (o.name + ".cpp"), source, o.force);
  write_file(dir / "CMakeLists.txt", lists, o.force);
  log << fmt::format(
      "wrote {0}/{1}.cpp and {0}/CMakeLists.txt\n"
      "build:  cmake -S {0} -B {0}/build -DCMAKE_PREFIX_PATH=<shard install prefix> && cmake --build {0}/build\n"
      "load:   shard --plugin-dir {0}/build/plugins plugins\n",
      dir.string(), o.name);
}

}  // namespace

void add_new_plugin_command(CLI::App& app, CommandContext& ctx) {
  auto options = std::make_shared<NewPluginOptions>();
  auto* cmd = app.add_subcommand("new-plugin", "write a one-file plugin template that builds against the installed Shard");
  cmd->add_option("kind", options->kind, "contact, bond or generator")->required();
  cmd->add_option("name", options->name, "plugin name as used in scenes, e.g. my_cohesion")->required();
  cmd->add_option("--dir", options->dir, "folder to write into (default: ./NAME)");
  cmd->add_option("--templates", options->template_dir, "template folder (default: installed share/shard/templates)");
  cmd->add_flag("--force", options->force, "overwrite existing files");
  cmd->callback([options, &ctx] {
    new_plugin(*options, std::cout);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
