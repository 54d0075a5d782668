#include "shard/analysis/process_report.hpp"

#include <fmt/format.h>

#include <fstream>
#include <ostream>
#include <stdexcept>

#include "shard/analysis/breakage_plot.hpp"
#include "shard/analysis/fsd_plot.hpp"
#include "shard/analysis/column_table.hpp"

namespace shard::analysis {
namespace {

std::string share_cell(const BreakageGroup& g) {
  if (g.plates == 0) return "-";
  return fmt::format("{:.2f} [{:.2f}, {:.2f}]", g.broken_share, g.broken_interval.lower, g.broken_interval.upper);
}

std::string x50_cell(const BreakageGroup& g) {
  if (g.fragments == 0) return "-";
  if (g.plates < 2) return fmt::format("{:.1f} (one plate: no interval)", g.x50 * 1e3);
  return fmt::format("{:.1f} [{:.1f}, {:.1f}]", g.x50 * 1e3, g.x50_interval.lower * 1e3, g.x50_interval.upper * 1e3);
}

}  // namespace

std::string markdown_group_table(const std::vector<BreakageGroup>& groups, GroupedBy by,
                                 const std::string& value_name) {
  std::string s;
  const std::string first = by == GroupedBy::impact_speed ? "impact speed [m/s]" : value_name;
  s += fmt::format("| {} | plates | broken | broken share [95 % Wilson] | impact speed mean (min-max) [m/s] | "
                   "fragments | x10 [mm] | x50 [mm] [95 % bootstrap] | x90 [mm] |\n",
                   first);
  s += "|---|---|---|---|---|---|---|---|---|\n";
  for (const BreakageGroup& g : groups) {
    const std::string key = by == GroupedBy::impact_speed ? fmt::format("{:.3f} - {:.3f}", g.lower, g.upper)
                                                          : fmt::format("{:g}", g.lower);
    const std::size_t impacted = g.plates - g.not_impacted;
    const std::string speed =
        impacted > 0 ? fmt::format("{:.3f} ({:.3f}-{:.3f})", g.mean_speed, g.min_speed, g.max_speed) : "-";
    const std::string sizes = g.fragments > 0 ? fmt::format("{:.1f} | {} | {:.1f}", g.x10 * 1e3, x50_cell(g), g.x90 * 1e3)
                                              : "- | - | -";
    s += fmt::format("| {} | {} | {} | {} | {}{} | {} | {} |\n", key, g.plates, g.broken, share_cell(g), speed,
                     g.not_impacted > 0 ? fmt::format(", {} without contact", g.not_impacted) : "", g.fragments,
                     sizes);
  }
  return s;
}

std::string markdown_plate_table(const std::vector<PlateOutcome>& plates, std::size_t max_rows,
                                 const std::string& value_name) {
  std::string s;
  const bool sweep = !value_name.empty();
  s += sweep ? fmt::format("| {} | seed | body | impact speed [m/s] | angle [deg] | fragments | largest fraction | "
                           "broken | x50 [mm] |\n|---|---|---|---|---|---|---|---|---|\n",
                           value_name)
             : std::string("| body | impact speed [m/s] | angle [deg] | fragments | largest fraction | broken | "
                           "x50 [mm] |\n|---|---|---|---|---|---|---|\n");
  const std::size_t shown = std::min(max_rows, plates.size());
  for (std::size_t k = 0; k < shown; ++k) {
    const PlateOutcome& p = plates[k];
    const std::string speed = p.impacted ? fmt::format("{:.3f}", p.impact_speed) : "-";
    const std::string angle = p.impacted ? fmt::format("{:.1f}", p.impact_angle) : "-";
    if (sweep) s += fmt::format("| {:g} | {} ", p.value, p.seed);
    s += fmt::format("| {} | {} | {} | {} | {:.3f} | {} | {:.1f} |\n", p.body, speed, angle, p.fragments,
                     p.largest_fraction, p.broken ? "yes" : "no", p.x50 * 1e3);
  }
  if (shown < plates.size()) s += fmt::format("\n... {} more plates in plates.csv\n", plates.size() - shown);
  return s;
}

std::string method_paragraph(const CurveOptions& options, double intact_fraction) {
  return fmt::format(
      "A plate is **broken** when its largest fragment holds less than {:g} of its mass. Its **impact** is its "
      "first wall contact (centre-of-mass speed and angle from the wall's inward normal, /body_impacts). The "
      "**broken share** of a group of n plates with k broken is k/n with the **Wilson score interval** "
      "({}): centre (k + z^2/2)/(n + z^2), half-width z sqrt(n)/(n + z^2) sqrt(p(1-p) + z^2/(4n)). "
      "**x50** is the mass-weighted median equivalent diameter of all fragments of the group's plates pooled; "
      "its interval is a **bootstrap percentile interval** ({:.0f} %): the plates are resampled with replacement "
      "{} times (a plate's fragments stay together), the pooled x50 recomputed each time, and the {:g} % and "
      "{:g} % quantiles taken (fixed seed {}: the same interval on every run). Speed bins are [lower, upper), the "
      "last closed; plates without a wall contact are left out of them. A group of one plate has no x50 interval.\n",
      intact_fraction, options.z == kZ95 ? std::string("95 %, z = 1.95996") : fmt::format("z = {:.6g}", options.z),
      100 * options.level, options.resamples,
      50 * (1 - options.level), 100 - 50 * (1 - options.level), options.seed);
}

void write_text_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

void write_run_breakage_report(RunFile& file, const RunBodies& bodies, double intact_fraction,
                               const RunReportOptions& options, std::ostream& out) {
  namespace fs = std::filesystem;
  fs::create_directories(options.dir);
  const std::vector<PlateOutcome> plates = plate_outcomes(bodies.report, bodies.fragments, file.path().string());
  const std::vector<double> edges =
      options.speed_edges.empty() ? speed_bin_edges(plates, options.speed_bins) : options.speed_edges;
  const std::vector<BreakageGroup> by_speed = breakage_by_speed(plates, edges, options.curve);
  std::vector<const PlateOutcome*> all;
  for (const PlateOutcome& p : plates) all.push_back(&p);
  const BreakageGroup total = breakage_group(all, options.curve);

  const ColumnTable speed_table = group_table(by_speed, GroupedBy::impact_speed, options.curve);
  write_csv(plate_table(plates), options.dir / "plates.csv");
  write_csv(speed_table, options.dir / "breakage_vs_speed.csv");
  const std::string group = fmt::format("/breakage/{}/by_impact_speed", frame_name(static_cast<std::size_t>(bodies.frame)));
  file.write_table(group, to_run_table(speed_table));

  const fs::path image = options.dir / "breakage_vs_speed.png";
  bool pictured = true;
  try {
    plot_breakage_curve(by_speed, plates, image,
                        {fmt::format("{} at t = {:.4g} s: breakage versus impact speed",
                                     file.path().filename().string(), bodies.time),
                         "impact speed [m/s]", false});
  } catch (const PlotError& e) {
    pictured = false;
    out << "warning: no picture: " << e.what() << "\n";
  }

  std::string page = fmt::format("# Breakage report: {}\n\n", file.path().string());
  if (!options.command.empty()) page += fmt::format("Made by `{}`.\n\n", options.command);
  page += fmt::format(
      "Frame {} (t = {:.6g} s): **{} plates, {} broken: breakage probability {:.3f} [{:.3f}, {:.3f}]** (95 % "
      "Wilson); {} without a wall contact. All fragments pooled: x10 {:.1f} mm, x50 {:.1f} mm [{:.1f}, {:.1f}], "
      "x90 {:.1f} mm.\n\n",
      bodies.frame, bodies.time, total.plates, total.broken, total.broken_share, total.broken_interval.lower,
      total.broken_interval.upper, total.not_impacted, total.x10 * 1e3, total.x50 * 1e3, total.x50_interval.lower * 1e3,
      total.x50_interval.upper * 1e3, total.x90 * 1e3);
  page += "## Breakage versus impact speed\n\n" + markdown_group_table(by_speed, GroupedBy::impact_speed) + "\n";
  if (pictured) page += "![breakage share and x50 versus impact speed](breakage_vs_speed.png)\n\n";
  page += "## Plates\n\n" + markdown_plate_table(plates, 200) + "\n";
  page += "## Method\n\n" + method_paragraph(options.curve, intact_fraction) + "\n";
  page += fmt::format(
      "## Files\n\n- `plates.csv`: one row per plate\n- `breakage_vs_speed.csv`: the table above (SI units)\n"
      "- `{}`: {} in the run file\n{}",
      group, "the same table", pictured ? "- `breakage_vs_speed.png` (+ `.gp` script and `.dat` data)\n" : "");
  write_text_file(options.dir / "report.md", page);
  out << fmt::format("wrote {} (report.md, plates.csv, breakage_vs_speed.csv{}) and {}\n", options.dir.string(),
                     pictured ? ", breakage_vs_speed.png" : "", group);
}

}  // namespace shard::analysis
