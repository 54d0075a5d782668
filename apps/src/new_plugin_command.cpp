// `shard new-plugin KIND NAME [--dir DIR]`: writes a one-file plugin and its CMakeLists.txt from
// the templates, ready to build out of tree against the installed Shard package (docs/how-to/write-a-plugin.md).
// `shard new-plugin --effect NAME`: a bond effect composed onto beam_bond (shard/bond_effect.hpp),
// its plugin source, a scaffold test and a CMakeLists.txt that builds and registers both.
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
#include <utility>
#include <vector>

#include "shard/app/commands.hpp"
#include "shard/install_layout.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

struct NewPluginOptions {
  std::string kind;
  std::string name;
  std::string effect;  // --effect NAME: a bond effect instead of KIND NAME
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

// Installed: <prefix>/share/shard/templates; in the build tree: the source's (install_layout.hpp).
std::vector<fs::path> template_search_path(const fs::path& explicit_dir) {
  std::vector<fs::path> dirs;
  if (!explicit_dir.empty()) dirs.push_back(explicit_dir);
  if (const char* env = std::getenv("SHARD_TEMPLATE_DIR")) dirs.emplace_back(env);
  dirs.push_back(install_layout().data_dir / "templates");
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

void check_name(const std::string& name) {
  if (!valid_name(name))
    throw std::invalid_argument(
        fmt::format("plugin name '{}': lower-case letters, digits and '_', starting with a letter", name));
}

// (template, file written) pairs, filled with the name, class and kind.
void write_from_templates(const NewPluginOptions& o, const std::string& name, const std::string& kind,
                          const std::vector<std::pair<std::string, std::string>>& files, const fs::path& dir) {
  const auto search = template_search_path(o.template_dir);
  auto fill = [&](std::string text) {
    text = substitute(std::move(text), "{{name}}", name);
    text = substitute(std::move(text), "{{class}}", class_name(name));
    return substitute(std::move(text), "{{kind}}", kind);
  };
  std::vector<std::string> texts;
  for (const auto& [from, to] : files) texts.push_back(fill(read_template(search, from)));
  fs::create_directories(dir);
  for (const auto& [from, to] : files)
    if (fs::exists(dir / to) && !o.force)
      throw std::runtime_error(fmt::format("{} exists; not overwritten (use --force)", (dir / to).string()));
  for (std::size_t k = 0; k < files.size(); ++k) write_file(dir / files[k].second, texts[k], o.force);
}

void new_effect(const NewPluginOptions& o, std::ostream& log) {
  check_name(o.effect);
  const std::string& name = o.effect;
  const fs::path dir = o.dir.empty() ? fs::path(name) : o.dir;
  write_from_templates(o, name, "bond_effect",
                       {{"bond_effect.hpp.in", name + ".hpp"},
                        {"bond_effect.cpp.in", name + ".cpp"},
                        {"bond_effect_test.cpp.in", "test_" + name + ".cpp"},
                        {"CMakeLists.effect.txt.in", "CMakeLists.txt"}},
                       dir);
  log << fmt::format(
      "wrote {0}/{1}.hpp (the effect), {0}/{1}.cpp (its registration onto beam_bond), {0}/test_{1}.cpp and "
      "{0}/CMakeLists.txt\n"
      "build:  cmake -S {0} -B {0}/build -DCMAKE_PREFIX_PATH=<shard install prefix> && cmake --build {0}/build\n"
      "test:   ctest --test-dir {0}/build\n"
      "use:    shard --plugin-dir {0}/build/plugins run SCENE --set bond.effects={1} "
      "--set bond.{1}_damage_per_strain=50\n",
      dir.string(), name);
}

void new_plugin(const NewPluginOptions& o, std::ostream& log) {
  if (!o.effect.empty()) {
    if (!o.kind.empty() || !o.name.empty())
      throw std::invalid_argument("shard new-plugin: give KIND NAME or --effect NAME, not both");
    new_effect(o, log);
    return;
  }
  if (o.kind.empty() || o.name.empty())
    throw std::invalid_argument("shard new-plugin needs KIND NAME (contact, bond or generator), or --effect NAME");
  if (o.kind != "contact" && o.kind != "bond" && o.kind != "generator")
    throw std::invalid_argument(fmt::format("unknown plugin kind '{}': contact, bond or generator", o.kind));
  check_name(o.name);
  const fs::path dir = o.dir.empty() ? fs::path(o.name) : o.dir;
  write_from_templates(o, o.name, o.kind,
                       {{o.kind + ".cpp.in", o.name + ".cpp"}, {"CMakeLists.txt.in", "CMakeLists.txt"}}, dir);
  log << fmt::format(
      "wrote {0}/{1}.cpp and {0}/CMakeLists.txt\n"
      "build:  cmake -S {0} -B {0}/build -DCMAKE_PREFIX_PATH=<shard install prefix> && cmake --build {0}/build\n"
      "load:   shard --plugin-dir {0}/build/plugins plugins\n",
      dir.string(), o.name);
}

}  // namespace

void add_new_plugin_command(CLI::App& app, CommandContext& ctx) {
  auto options = std::make_shared<NewPluginOptions>();
  auto* cmd = app.add_subcommand("new-plugin", "write a plugin template that builds against the installed Shard");
  cmd->add_option("kind", options->kind, "contact, bond or generator");
  cmd->add_option("name", options->name, "plugin name as used in scenes, e.g. my_cohesion");
  cmd->add_option("--effect", options->effect,
                  "instead of KIND NAME: a bond effect NAME composed onto beam_bond, with a scaffold test");
  cmd->add_option("--dir", options->dir, "folder to write into (default: ./NAME)");
  cmd->add_option("--templates", options->template_dir, "template folder (default: installed share/shard/templates)");
  cmd->add_flag("--force", options->force, "overwrite existing files");
  cmd->callback([options, &ctx] {
    new_plugin(*options, std::cout);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
