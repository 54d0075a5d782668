#pragma once
// One spelling per question, one implementation per answer:
// - `shard calibrate --with EFFECT` is the measurement loop's calibration (calibrate-effect);
//   with --reference as well it fits one set's difference from the reference
//   (calibrate-contrast). Without --with, calibrate is the bending calibration.
// - `shard diagnose` with --reference, or with two or more measurement folders (folders holding
//   specimens.csv), is the contrast diagnosis across sets (diagnose-sets).
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace shard {

// args as main() received them (args[0] the program). Returns true when it renamed the command.
bool route_measurement_command(std::vector<std::string>& args);

// For `shard calibrate --help` and `shard diagnose --help` when no option picks a form yet: the
// help of every form the word stands for (each form's own --help, under a line saying which
// options pick it). Empty for any other command line.
std::optional<std::string> forms_help(const CLI::App& app, const std::vector<std::string>& args);

}  // namespace shard
