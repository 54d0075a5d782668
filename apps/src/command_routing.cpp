#include "shard/app/command_routing.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <string_view>

namespace shard {
namespace {

// The forms of each routed word, in the order their help is shown; `picked_by` says which
// options choose the form, as routed_form() below decides.
struct CommandForm {
  std::string_view word;
  std::string_view subcommand;
  std::string_view picked_by;
};
constexpr CommandForm kForms[] = {
    {"calibrate", "calibrate", "shard calibrate SCENE (no --with): four-point bending calibration of E and F_max"},
    {"calibrate", "calibrate-effect",
     "shard calibrate MEASUREMENTS --with EFFECT (no --reference): add an effect to the model and fit it"},
    {"calibrate", "calibrate-contrast",
     "shard calibrate SETS --reference REF --with EFFECT: fit an effect to one set's difference from REF"},
    {"diagnose", "diagnose", "shard diagnose MEASUREMENTS (one folder, no --reference): effects missing in one set"},
    {"diagnose", "diagnose-sets",
     "shard diagnose REF A B ... --reference REF (or two or more measurement folders): contrasts across sets"},
};

bool has_option(const std::vector<std::string>& args, std::size_t from, std::string_view name) {
  for (std::size_t k = from; k < args.size(); ++k) {
    const std::string_view a = args[k];
    if (a == "--") break;
    if (a == name || (a.starts_with(name) && a.size() > name.size() && a[name.size()] == '=')) return true;
  }
  return false;
}

std::size_t measurement_folders(const std::vector<std::string>& args, std::size_t from) {
  std::size_t n = 0;
  std::error_code ec;
  for (std::size_t k = from; k < args.size(); ++k)
    if (!args[k].starts_with("-") && std::filesystem::is_regular_file(std::filesystem::path(args[k]) / "specimens.csv", ec))
      ++n;
  return n;
}

// The index of the sub-command: the first word that is not an option or the value of
// --plugin-dir; 0 when there is none.
std::size_t command_word(const std::vector<std::string>& args) {
  for (std::size_t k = 1; k < args.size(); ++k) {
    if (args[k] == "--plugin-dir") {
      ++k;
      continue;
    }
    if (!args[k].starts_with("-")) return k;
  }
  return 0;
}

// The sub-command the options pick for the word at `command`, or "" when the word stands as given.
std::string_view routed_form(const std::vector<std::string>& args, std::size_t command) {
  const std::string_view word = args[command];
  if (word == "calibrate" && has_option(args, command + 1, "--with"))
    return has_option(args, command + 1, "--reference") ? "calibrate-contrast" : "calibrate-effect";
  if (word == "diagnose" &&
      (has_option(args, command + 1, "--reference") || measurement_folders(args, command + 1) >= 2))
    return "diagnose-sets";
  return {};
}

}  // namespace

bool route_measurement_command(std::vector<std::string>& args) {
  const std::size_t command = command_word(args);
  if (command == 0) return false;
  const std::string_view form = routed_form(args, command);
  if (form.empty()) return false;
  args[command] = std::string(form);
  return true;
}

std::optional<std::string> forms_help(const CLI::App& app, const std::vector<std::string>& args) {
  const std::size_t command = command_word(args);
  if (command == 0 || !routed_form(args, command).empty()) return std::nullopt;
  if (!has_option(args, command + 1, "--help") && !has_option(args, command + 1, "-h")) return std::nullopt;
  std::string summary, sections;
  std::size_t forms = 0;
  for (const auto& form : kForms) {
    if (form.word != args[command]) continue;
    ++forms;
    summary += fmt::format("  {}\n", form.picked_by);
    sections += fmt::format("\n=== form {}: {} ===\n{}", forms, form.picked_by,
                            app.get_subcommand(std::string(form.subcommand))->help("shard"));
  }
  if (forms == 0) return std::nullopt;
  return fmt::format("shard {} has {} forms; the options given pick one:\n{}{}", args[command], forms, summary,
                     sections);
}

}  // namespace shard
