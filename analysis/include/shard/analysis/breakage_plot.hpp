#pragma once
// The breakage curve as a picture, drawn by gnuplot (as fsd_plot.hpp: data and script beside the
// image, gnuplot started without a shell): above, the broken share of each group with its
// interval and every plate as a dot at 0 (intact) or 1 (broken); below, the pooled x50 of each
// group with its interval over the band from the pooled x10 to x90.
#include <filesystem>
#include <string>
#include <vector>

#include "shard/analysis/breakage_curve.hpp"
#include "shard/analysis/plate_outcome.hpp"

namespace shard::analysis {

struct BreakagePlot {
  std::string title;
  std::string x_label;   // "impact speed [m/s]" or the swept key
  bool by_value = false; // groups and plates placed at PlateOutcome::value, else at impact speed
};

// Writes <image>.dat, <image>.plates.dat and <image>.gp; the image must end in .png or .svg.
std::filesystem::path write_breakage_plot_script(const std::vector<BreakageGroup>& groups,
                                                 const std::vector<PlateOutcome>& plates,
                                                 const std::filesystem::path& image, const BreakagePlot& plot);

// The script, then gnuplot on it. Throws PlotError when gnuplot is missing or fails.
void plot_breakage_curve(const std::vector<BreakageGroup>& groups, const std::vector<PlateOutcome>& plates,
                         const std::filesystem::path& image, const BreakagePlot& plot);

}  // namespace shard::analysis
