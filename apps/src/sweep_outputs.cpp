#include "sweep_outputs.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <ostream>

#include "shard/analysis/breakage_plot.hpp"
#include "shard/analysis/breakage_tables.hpp"
#include "shard/analysis/column_table.hpp"
#include "shard/analysis/fsd_plot.hpp"
#include "shard/analysis/process_report.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using analysis::ColumnTable;

ColumnTable run_table(const SweepResult& result) {
  ColumnTable t;
  std::vector<double> value, wall, share, x50;
  std::vector<std::int64_t> seed, plates, broken, ok;
  std::vector<std::string> label, error, file;
  for (const SweepRun& r : result.runs) {
    value.push_back(r.value);
    seed.push_back(r.seed);
    label.push_back(r.label);
    ok.push_back(r.failed() ? 0 : 1);
    error.push_back(r.error);
    wall.push_back(r.wall_seconds);
    plates.push_back(static_cast<std::int64_t>(r.plates));
    broken.push_back(static_cast<std::int64_t>(r.broken));
    share.push_back(r.plates > 0 ? static_cast<double>(r.broken) / static_cast<double>(r.plates) : 0.0);
    x50.push_back(r.x50);
    file.push_back(r.run_file.string());
  }
  t.add("run", label).add("value", value).add("seed", seed).add("ran", ok).add("plates", plates).add("broken", broken);
  t.add("broken_share", share).add("x50_m", x50).add("wall_seconds", wall).add("run_file", file).add("error", error);
  t.note("value", result.value_label);
  t.note("description", "one row per (value, seed) run; x50 of all its fragments pooled");
  return t;
}

std::string run_lines(const SweepResult& result) {
  std::string s = "| run | value | seed | plates | broken | x50 [mm] | wall [s] | status |\n|---|---|---|---|---|---|---|---|\n";
  for (const SweepRun& r : result.runs)
    s += r.failed() ? fmt::format("| {} | {:g} | {} | - | - | - | - | failed: {} |\n", r.label, r.value, r.seed,
                                  r.error.substr(0, r.error.find('\n')))
                    : fmt::format("| {} | {:g} | {} | {} | {} | {:.1f} | {:.1f} | ran |\n", r.label, r.value, r.seed,
                                  r.plates, r.broken, r.x50 * 1e3, r.wall_seconds);
  return s;
}

// Draws one picture; a missing gnuplot is a warning, not a failed sweep.
bool picture(const std::vector<analysis::BreakageGroup>& groups, const SweepResult& result, const fs::path& image,
             const analysis::BreakagePlot& plot, std::ostream& log) {
  try {
    analysis::plot_breakage_curve(groups, result.plates, image, plot);
    return true;
  } catch (const analysis::PlotError& e) {
    fmt::print(log, "warning: no {}: {}\n", image.filename().string(), e.what());
    return false;
  }
}

}  // namespace

void write_sweep_outputs(const SweepOptions& options, const SweepPlan& plan, const SweepResult& result,
                         const analysis::CurveOptions& curve, std::ostream& log) {
  const fs::path& dir = options.out;
  const ColumnTable plates = analysis::plate_table(result.plates, "value");
  const ColumnTable runs = run_table(result);
  ColumnTable by_value = analysis::group_table(result.by_value, analysis::GroupedBy::value, curve, "value");
  by_value.note("value", result.value_label);
  const ColumnTable by_speed = analysis::group_table(result.by_speed, analysis::GroupedBy::impact_speed, curve);
  analysis::write_csv(plates, dir / "plates.csv");
  analysis::write_csv(runs, dir / "runs.csv");
  analysis::write_csv(by_value, dir / "breakage_vs_value.csv");
  analysis::write_csv(by_speed, dir / "breakage_vs_speed.csv");
  const fs::path h5 = dir / "sweep.h5";
  std::error_code ignored;
  fs::remove(h5, ignored);  // an earlier sweep's tables
  analysis::write_hdf5_table(h5, "/runs", runs);
  analysis::write_hdf5_table(h5, "/plates", plates);
  analysis::write_hdf5_table(h5, "/by_value", by_value);
  analysis::write_hdf5_table(h5, "/by_impact_speed", by_speed);

  const std::string scene = options.scene.filename().string();
  const bool speed_png = !result.plates.empty() &&
                         picture(result.by_speed, result, dir / "breakage_vs_speed.png",
                                 {fmt::format("{}: breakage versus impact speed ({} plates, {} runs)", scene,
                                              result.plates.size(), result.runs.size() - result.failed()),
                                  "impact speed [m/s]", false},
                                 log);
  const bool value_png = !result.plates.empty() &&
                         picture(result.by_value, result, dir / "breakage_vs_value.png",
                                 {fmt::format("{}: breakage versus {}", scene, plan.value_label), plan.value_label, true},
                                 log);

  std::vector<const analysis::PlateOutcome*> all;
  for (const auto& p : result.plates) all.push_back(&p);
  const analysis::BreakageGroup total = analysis::breakage_group(all, curve);
  std::string page = fmt::format("# Sweep of {}: {}\n\n", options.scene.string(), plan.value_label);
  if (!options.command_line.empty()) page += fmt::format("Made by `{}`.\n\n", options.command_line);
  page += fmt::format(
      "{} runs ({} values x {} seeds), {} failed, {} wall. **{} plates, {} broken: breakage probability {:.3f} "
      "[{:.3f}, {:.3f}]** (95 % Wilson); pooled x50 {:.1f} mm [{:.1f}, {:.1f}] (95 % bootstrap).\n\n",
      result.runs.size(), plan.vary.values.size(), options.seeds, result.failed(),
      fmt::format("{:.0f} s", result.wall_seconds), total.plates, total.broken, total.broken_share,
      total.broken_interval.lower, total.broken_interval.upper, total.x50 * 1e3, total.x50_interval.lower * 1e3,
      total.x50_interval.upper * 1e3);
  if (!options.sets.empty()) {
    page += "Every run with:";
    for (const auto& s : options.sets) page += fmt::format(" `--set {}`", s);
    page += "\n\n";
  }
  page += fmt::format("## Breakage versus {}\n\n", plan.value_label) +
          analysis::markdown_group_table(result.by_value, analysis::GroupedBy::value, plan.value_name) + "\n";
  if (value_png) page += "![breakage share and x50 versus the swept value](breakage_vs_value.png)\n\n";
  page += "## Breakage versus impact speed (all plates pooled)\n\n" +
          analysis::markdown_group_table(result.by_speed, analysis::GroupedBy::impact_speed) + "\n";
  if (speed_png) page += "![breakage share and x50 versus impact speed](breakage_vs_speed.png)\n\n";
  page += "## Runs\n\n" + run_lines(result) + "\n";
  page += "## Plates\n\n" + analysis::markdown_plate_table(result.plates, 120, plan.value_name) + "\n";
  page += "## Method\n\n" + analysis::method_paragraph(curve, options.intact_fraction);
  page += fmt::format(
      "Seed index s adds s to the scene's [simulation] seed (the packing) and to every [body.stream] seed "
      "(orientations, positions, speed scatter); s = 0 is the scene as written. The per-run tables are the "
      "ones `shard fragments RUN.h5 --by-body` prints (also written to /bodies/<k> of each run file).\n\n");
  page += "## Files\n\n- `runs.csv`, `plates.csv`, `breakage_vs_value.csv`, `breakage_vs_speed.csv` (SI units)\n"
          "- `sweep.h5`: the same tables as groups /runs, /plates, /by_value, /by_impact_speed\n"
          "- `runs/<run>/run.h5`: every run (ParaView: run.xmf)\n";
  analysis::write_text_file(dir / "report.md", page);
  if (!options.quiet) {
    fmt::print(log, "sweep: {} plates in {} runs ({} failed), {} broken: breakage probability {:.3f} [{:.3f}, {:.3f}]\n",
               total.plates, result.runs.size() - result.failed(), result.failed(), total.broken, total.broken_share,
               total.broken_interval.lower, total.broken_interval.upper);
    for (const auto& g : result.by_value)
      fmt::print(log, "  {} = {:g}: {} plates, {} broken, share {:.2f} [{:.2f}, {:.2f}], x50 {:.1f} mm [{:.1f}, {:.1f}]\n",
                 plan.value_name, g.lower, g.plates, g.broken, g.broken_share, g.broken_interval.lower,
                 g.broken_interval.upper, g.x50 * 1e3, g.x50_interval.lower * 1e3, g.x50_interval.upper * 1e3);
    fmt::print(log, "wrote {}/report.md, runs.csv, plates.csv, breakage_vs_value.csv, breakage_vs_speed.csv, sweep.h5{}{}\n",
               dir.string(), value_png ? ", breakage_vs_value.png" : "", speed_png ? ", breakage_vs_speed.png" : "");
  }
}

}  // namespace shard
