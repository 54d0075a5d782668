#pragma once
// The force-displacement figure of a bending test: the curve, the fitted initial stiffness, the
// peak, and F_max, w_s,max, E and sigma_b written on it. gnuplot (Debian gnuplot-nox) draws it;
// the data and script are kept beside the image (<image>.dat, <image>.gp).
#include <filesystem>
#include <string>

#include "shard/bending/curve_analysis.hpp"

namespace shard::bending {

// Writes <image>.dat and <image>.gp and returns the script path (terminal from the extension:
// .png pngcairo, .svg svg). Throws analysis::PlotError for another extension.
std::filesystem::path write_bending_plot_script(const analysis::LoadCurve& curve, const CurveAnalysis& a,
                                                const std::filesystem::path& image, const std::string& title);
// ... and runs gnuplot; throws analysis::PlotError when gnuplot is missing or fails.
void plot_bending_curve(const analysis::LoadCurve& curve, const CurveAnalysis& a, const std::filesystem::path& image,
                        const std::string& title);

}  // namespace shard::bending
