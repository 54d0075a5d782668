#pragma once
// A picture of the fragment size distribution, drawn by gnuplot (Debian: gnuplot-nox).
// The data and the script are written beside the image (<image>.dat, <image>.gp) so the figure
// can be restyled by hand; gnuplot is started directly (posix_spawn, no shell), so no path or
// title can be interpreted as a command.
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/analysis/size_distribution.hpp"

namespace shard::analysis {

class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The first executable named `name` on PATH, if any.
std::optional<std::filesystem::path> find_program(const std::string& name);

// Runs program with args (no shell), waits, returns its exit status (128 + signal if killed).
// Throws PlotError if it cannot be started.
int run_program(const std::filesystem::path& program, const std::vector<std::string>& args);

// Quotes text as a gnuplot single-quoted string ('' stands for ').
std::string gnuplot_quote(const std::string& text);

// Writes the script for image (terminal from the extension: .png -> pngcairo, .svg -> svg).
// Returns the script path. Throws PlotError for another extension or an unwritable folder.
std::filesystem::path write_fsd_plot_script(const SizeDistribution& fsd,
                                            const std::filesystem::path& image,
                                            const std::string& title);

// Writes data and script and runs gnuplot. Throws PlotError with a clear message if gnuplot is
// not installed or fails.
void plot_size_distribution(const SizeDistribution& fsd, const std::filesystem::path& image,
                            const std::string& title);

}  // namespace shard::analysis
