#pragma once
// One spelling per question, one implementation per answer:
// - `shard calibrate --with EFFECT` is the measurement loop's calibration (calibrate-effect);
//   with --reference as well it fits one set's difference from the reference
//   (calibrate-contrast). Without --with, calibrate is the bending calibration.
// - `shard diagnose` with --reference, or with two or more measurement folders (folders holding
//   specimens.csv), is the contrast diagnosis across sets (diagnose-sets).
#include <string>
#include <vector>

namespace shard {

// args as main() received them (args[0] the program). Returns true when it renamed the command.
bool route_measurement_command(std::vector<std::string>& args);

}  // namespace shard
