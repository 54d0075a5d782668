#include "shard/app/command_routing.hpp"

#include <filesystem>
#include <string_view>

namespace shard {
namespace {

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

}  // namespace

bool route_measurement_command(std::vector<std::string>& args) {
  // The sub-command is the first word that is not an option or the value of --plugin-dir.
  std::size_t command = 0;
  for (std::size_t k = 1; k < args.size(); ++k) {
    if (args[k] == "--plugin-dir") {
      ++k;
      continue;
    }
    if (!args[k].starts_with("-")) {
      command = k;
      break;
    }
  }
  if (command == 0) return false;
  if (args[command] == "calibrate" && has_option(args, command + 1, "--with")) {
    args[command] = has_option(args, command + 1, "--reference") ? "calibrate-contrast" : "calibrate-effect";
    return true;
  }
  if (args[command] == "diagnose" &&
      (has_option(args, command + 1, "--reference") || measurement_folders(args, command + 1) >= 2)) {
    args[command] = "diagnose-sets";
    return true;
  }
  return false;
}

}  // namespace shard
