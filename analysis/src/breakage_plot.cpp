#include "shard/analysis/breakage_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>

#include "shard/analysis/fsd_plot.hpp"

namespace shard::analysis {
namespace {

std::string terminal_for(const std::filesystem::path& image) {
  const std::string extension = image.extension().string();
  if (extension == ".png") return "pngcairo size 900,800 enhanced font 'Sans,11'";
  if (extension == ".svg") return "svg size 900,800 enhanced font 'Sans,11'";
  throw PlotError("plot file must end in .png or .svg: " + image.string());
}

// The x range of the groups and plates drawn and the range of the fragment sizes, grown as the
// data files are written.
struct PlotRanges {
  double x_min = 0, x_max = 0, size_min = 0, size_max = 0;
  bool any = false, any_size = false;

  void extend(double x) {
    x_min = any ? std::min(x_min, x) : x;
    x_max = any ? std::max(x_max, x) : x;
    any = true;
  }
  void extend_sizes(const BreakageGroup& g) {
    size_min = any_size ? std::min(size_min, g.x10) : g.x10;
    size_max = any_size ? std::max({size_max, g.x90, g.x50_interval.upper}) : std::max(g.x90, g.x50_interval.upper);
    any_size = true;
  }
};

// One line per group that has plates: its x, breakage share and pooled sizes with their intervals.
void write_group_data(const std::vector<BreakageGroup>& groups, const std::filesystem::path& data,
                      const BreakagePlot& plot, PlotRanges& ranges) {
  std::ofstream out(data);
  if (!out) throw PlotError("cannot write " + data.string());
  out << "# x x_low x_high broken_share share_low share_high x50[mm] x50_low[mm] x50_high[mm] plates x10[mm] "
         "x90[mm]\n";
  for (const BreakageGroup& g : groups) {
    if (g.plates == 0) continue;
    // A speed bin is drawn at its plates' mean speed, spanning the bin; a value at itself.
    const double x = plot.by_value ? g.lower : g.mean_speed;
    ranges.extend(g.lower);
    ranges.extend(g.upper);
    if (g.fragments > 0) ranges.extend_sizes(g);
    out << fmt::format("{:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {} {:.9g} {:.9g}\n", x, g.lower,
                       g.upper, g.broken_share, g.broken_interval.lower, g.broken_interval.upper, g.x50 * 1e3,
                       g.x50_interval.lower * 1e3, g.x50_interval.upper * 1e3, g.plates, g.x10 * 1e3, g.x90 * 1e3);
  }
}

// One line per plate drawn (by speed: only the plates that hit a wall).
void write_plate_data(const std::vector<PlateOutcome>& plates, const std::filesystem::path& plate_data,
                      const BreakagePlot& plot, PlotRanges& ranges) {
  std::ofstream out(plate_data);
  if (!out) throw PlotError("cannot write " + plate_data.string());
  out << "# x broken(0/1) x50[mm]  (one line per plate; x50 of its own fragments)\n";
  for (const PlateOutcome& p : plates) {
    if (!plot.by_value && !p.impacted) continue;
    const double x = plot.by_value ? p.value : p.impact_speed;
    if (!plot.by_value) ranges.extend(x);
    out << fmt::format("{:.9g} {} {:.9g}\n", x, p.broken ? 1 : 0, p.x50 * 1e3);
  }
}

// The gnuplot commands: the broken share over x above, the pooled fragment sizes below.
void write_plot_commands(std::ostream& out, const std::string& terminal, const std::filesystem::path& image,
                         const std::filesystem::path& data, const std::filesystem::path& plate_data,
                         const BreakagePlot& plot, const PlotRanges& ranges) {
  const double span = ranges.x_max > ranges.x_min ? ranges.x_max - ranges.x_min
                                                  : std::max(0.1 * std::abs(ranges.x_max), 1e-3);
  const double lo = ranges.x_min - 0.08 * span, hi = ranges.x_max + 0.08 * span;
  out << "set terminal " << terminal << "\n";
  out << "set output " << gnuplot_quote(image.string()) << "\n";
  out << "set multiplot layout 2,1 title " << gnuplot_quote(plot.title) << " noenhanced\n";
  out << "set grid\nset key outside below horizontal\nset lmargin 10\n";
  out << fmt::format("set xrange [{:.9g}:{:.9g}]\n", lo, hi);
  out << "set xlabel " << gnuplot_quote(plot.x_label) << " noenhanced\n";
  out << "set ylabel 'broken share'\nset yrange [-0.05:1.05]\n";
  const std::string d = gnuplot_quote(data.string()), pl = gnuplot_quote(plate_data.string());
  const std::string group_bars = plot.by_value ? "1:4:5:6 with yerrorbars" : "1:4:2:3:5:6 with xyerrorbars";
  out << fmt::format(
      "plot {0} using 1:2 with points pt 6 ps 1.0 lc rgb '#555555' title 'plates "
      "(1 broken, 0 intact)', \\\n  {1} using {2} pt 7 ps 1.2 lw 2 lc rgb '#b2182b' title 'broken share, 95 % "
      "Wilson', \\\n  {1} using 1:4 with lines lw 1 lc rgb '#b2182b' notitle\n",
      pl, d, group_bars);
  out << "set ylabel 'fragment size d_{eq} [mm]'\n";
  // A range of its own: one group of one-size fragments would give gnuplot an empty one.
  const double size_max = ranges.size_max, size_min = ranges.size_min;
  const double size_pad = std::max(0.1 * (size_max - size_min), 0.05 * size_max);
  out << fmt::format("set yrange [{:.9g}:{:.9g}]\n", std::max(0.0, size_min - size_pad) * 1e3,
                     (size_max + size_pad) * 1e3 + (size_max > 0 ? 0.0 : 1.0));
  // The pooled distribution of each group: x50 with its interval, x10 and x90 as a band. (A
  // plate's own x50 is left out: with one chip off an intact plate it interpolates halfway between
  // chip and plate, which says little about the product.)
  const std::string x50_bars = plot.by_value ? "1:7:8:9 with yerrorbars" : "1:7:2:3:8:9 with xyerrorbars";
  out << fmt::format(
      "plot {0} using 1:11:12 with filledcurves fc rgb '#d1e5f0' fs solid 0.6 title 'pooled x_{{10}} to x_{{90}}', "
      "\\\n  {0} using {1} pt 7 ps 1.2 lw 2 lc rgb '#2166ac' title 'pooled x_{{50}}, 95 % bootstrap', \\\n"
      "  {0} using 1:7 with lines lw 1 lc rgb '#2166ac' notitle\n",
      d, x50_bars);
  out << "unset multiplot\n";
}

}  // namespace

std::filesystem::path write_breakage_plot_script(const std::vector<BreakageGroup>& groups,
                                                 const std::vector<PlateOutcome>& plates,
                                                 const std::filesystem::path& image, const BreakagePlot& plot) {
  const std::string terminal = terminal_for(image);
  std::filesystem::path data = image, plate_data = image, script = image;
  data += ".dat";
  plate_data += ".plates.dat";
  script += ".gp";
  PlotRanges ranges;
  write_group_data(groups, data, plot, ranges);
  if (!ranges.any)
    throw PlotError(plot.by_value ? "no plate to plot" : "no plate touched a wall: no impact speed to plot");
  write_plate_data(plates, plate_data, plot, ranges);
  std::ofstream out(script);
  if (!out) throw PlotError("cannot write " + script.string());
  write_plot_commands(out, terminal, image, data, plate_data, plot, ranges);
  if (!out) throw PlotError("cannot write " + script.string());
  return script;
}

void plot_breakage_curve(const std::vector<BreakageGroup>& groups, const std::vector<PlateOutcome>& plates,
                         const std::filesystem::path& image, const BreakagePlot& plot) {
  const auto gnuplot = find_program("gnuplot");
  if (!gnuplot)
    throw PlotError("gnuplot is not installed (on Debian: apt-get install gnuplot-nox); the tables are written as CSV");
  const std::filesystem::path script = write_breakage_plot_script(groups, plates, image, plot);
  const int status = run_program(*gnuplot, {script.string()});
  if (status != 0)
    throw PlotError("gnuplot failed (exit status " + std::to_string(status) + ") on " + script.string());
  if (!std::filesystem::exists(image)) throw PlotError("gnuplot wrote no " + image.string());
}

}  // namespace shard::analysis
