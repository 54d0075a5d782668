#include "shard/app/command_routing.hpp"

#include <string_view>

namespace shard {

bool route_calibrate_with(std::vector<std::string>& args) {
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
  if (command == 0 || args[command] != "calibrate") return false;
  for (std::size_t k = command + 1; k < args.size(); ++k) {
    const std::string_view a = args[k];
    if (a == "--") break;
    if (a == "--with" || a.starts_with("--with=")) {
      args[command] = "calibrate-effect";
      return true;
    }
  }
  return false;
}

}  // namespace shard
