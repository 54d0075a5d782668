#include "shard/app/run_ensemble.hpp"

#include <algorithm>
#include <array>
#include <string_view>

namespace shard {

bool spreads_runs_over_ranks(const std::vector<std::string>& args) {
  // Every command that simulates through the RunPool (measure_runner.hpp).
  static constexpr std::array<std::string_view, 6> kEnsembleCommands{
      "synth", "compare", "diagnose", "diagnose-sets", "calibrate-effect", "calibrate-contrast"};
  // The sub-command is the first word that is not an option or the value of --plugin-dir.
  for (std::size_t k = 1; k < args.size(); ++k) {
    if (args[k] == "--plugin-dir") {
      ++k;
      continue;
    }
    if (args[k].starts_with("-")) continue;
    return std::find(kEnsembleCommands.begin(), kEnsembleCommands.end(), args[k]) != kEnsembleCommands.end();
  }
  return false;
}

}  // namespace shard
