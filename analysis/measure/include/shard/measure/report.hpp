#pragma once
// A comparison as Markdown and JSON tables, and as a two-panel gnuplot figure: measured curves
// with the band of their mean, simulated curves, and the standardised residual with +-2 sigma and
// the failing regimes shaded.
#include <filesystem>
#include <string>

#include "shard/io/json.hpp"
#include "shard/measure/comparison.hpp"

namespace shard::measure {

std::string comparison_markdown(const Comparison& c);
// The comparison's features, regimes and verdict as a JSON object (compare.json holds one per
// loading rate); non-finite numbers are written as null by shard::io.
io::Json comparison_json(const Comparison& c);

// Writes <image>.dat and <image>.gp next to the image and runs gnuplot (pngcairo for .png,
// svg for .svg). Throws when gnuplot is missing or fails.
void plot_comparison(const Comparison& c, const std::filesystem::path& image, const std::string& title);

// Runs `program args...` and waits; returns its exit status (-1 when it could not start).
int run_program(const std::string& program, const std::vector<std::string>& args);

}  // namespace shard::measure
