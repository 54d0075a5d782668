#pragma once
// `shard calibrate --with EFFECT` is the measurement loop's calibration (the name issue 7 and the
// tutorial give it); its options are calibrate-effect's. This routes such a command line there,
// so both spellings run one implementation. Without --with, calibrate is the bending calibration.
#include <string>
#include <vector>

namespace shard {

// args as main() received them (args[0] the program). Returns true when it renamed the command.
bool route_calibrate_with(std::vector<std::string>& args);

}  // namespace shard
