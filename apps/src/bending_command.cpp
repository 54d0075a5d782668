// `shard bending run.h5`: the four-point bending report and plot (seed sec. IV-V).
// `shard calibrate scene.toml`: E_b then sigma_crit tuned until E and F_max meet their targets.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <fstream>
#include <functional>
#include <map>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "bending_commands.hpp"
#include "option_checks.hpp"
#include "shard/driver/output_folder.hpp"
#include "shard/app/commands.hpp"
#include "shard/app/run_command.hpp"
#include "shard/bending/bending_plot.hpp"
#include "shard/bending/bending_run.hpp"
#include "shard/bending/calibration.hpp"
#include "shard/io/json.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"
#include "shard/measure/significant_digits.hpp"

namespace shard {
namespace {

struct BendingCliOptions {
  std::filesystem::path run;
  std::string plot;     // default: <run stem>_bending.png beside the run
  bool no_plot = false;
  std::string json;     // default: <run stem>_bending.json
  bending::BendingOptions analysis;
  double span_mm = 0, pins_mm = 0, width_mm = 0, height_mm = 0;
};

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  out << text;
}

std::filesystem::path beside(const std::filesystem::path& run, const std::string& suffix) {
  return run.parent_path() / (run.stem().string() + suffix);
}

void add_geometry_options(CLI::App& cmd, BendingCliOptions& o) {
  cmd.add_option("--span", o.span_mm, "support span in mm (default: from the support walls)");
  cmd.add_option("--pin-distance", o.pins_mm, "loading-pin distance in mm (default: from the pin walls)");
  cmd.add_option("--width", o.width_mm, "specimen width in mm (default: sphere extent)");
  cmd.add_option("--height", o.height_mm, "specimen height in mm (default: sphere extent)");
  cmd.add_option("--fit-low", o.analysis.curve.fit_low, "stiffness fit from this fraction of F_max (default 0.1)");
  cmd.add_option("--fit-high", o.analysis.curve.fit_high, "... to this fraction (default 0.4)");
}

void apply_geometry(BendingCliOptions& o) {
  if (o.span_mm > 0) o.analysis.span = 1e-3 * o.span_mm;
  if (o.pins_mm > 0) o.analysis.pin_distance = 1e-3 * o.pins_mm;
  if (o.width_mm > 0) o.analysis.width = 1e-3 * o.width_mm;
  if (o.height_mm > 0) o.analysis.height = 1e-3 * o.height_mm;
}

int bending_command(BendingCliOptions& o) {
  apply_geometry(o);
  const auto report = bending::analyse_bending_run(o.run, o.analysis);
  fmt::print("{}", bending::format_report(report));
  const auto json = o.json.empty() ? beside(o.run, "_bending.json") : std::filesystem::path(o.json);
  io::write_json(json, bending::report_json(report));
  const auto csv = beside(o.run, "_bending_curve.csv");
  bending::write_curve_csv(csv.string(), report.curve);
  const auto local_csv = beside(o.run, "_local_curve.csv");
  bending::write_curve_csv(local_csv.string(), report.local_curve);
  fmt::print("  wrote {}, {} (pin travel) and {} (beam deflection under the pins)\n", json.string(), csv.string(),
             local_csv.string());
  if (!o.no_plot) {
    const auto image = o.plot.empty() ? beside(o.run, "_bending.png") : std::filesystem::path(o.plot);
    bending::plot_bending_curve(report.curve, report.analysis, image,
                                fmt::format("four-point bending: {}", o.run.string()));
    fmt::print("  plot {}\n", image.string());
  }
  return 0;
}

struct CalibrateCliOptions {
  std::filesystem::path scene;
  std::vector<std::string> overrides;
  std::filesystem::path out_dir = "calibration";
  double target_e = 13.2e6;
  bool target_e_given = false;  // --target-E on the command line wins over a measurement's E
  double target_strength = 0, target_fmax = 0;
  std::string measurement;
  double tolerance = 0.03;
  int max_runs = 20;
  int threads = 0;
  double lab_span_mm = 180.0;       // span of the measured specimen (--measurement)
  double stiffness_fraction = 0.7;  // stiffness runs stop at this fraction of the target F_max's pin travel
  std::string modulus = "local";    // which E is calibrated: local instrumentation or pin travel
  BendingCliOptions geometry;
};

// The bond's current parameters, from the scene as it would run.
std::pair<double, double> scene_bond_parameters(const CalibrateCliOptions& o, const PluginHost& host) {
  const Scene scene = load_scene(o.scene, o.overrides, host);
  if (!scene.bond || scene.bond->name != "beam_bond")
    throw std::runtime_error(fmt::format("{}: calibration needs a [bond] section with plugin = \"beam_bond\"",
                                         o.scene.string()));
  return {scene.bond->params.number("youngs_modulus"), scene.bond->params.number("critical_stress")};
}

// What the calibration aims at: E always; F_max given, or a strength (a measured curve's or
// --target-strength) that becomes an F_max once a run has shown the specimen's geometry.
struct CalibrationAims {
  bending::CalibrationTargets targets;
  std::optional<double> strength;  // Pa, sigma_b (eq. 15)
};

double metadata_number(const CalibrateCliOptions& o, const std::map<std::string, std::string>& meta, const char* key,
                       double fallback) {
  const auto it = meta.find(key);
  if (it == meta.end()) return fallback;
  try {
    return std::stod(it->second);
  } catch (const std::exception&) {
    throw std::runtime_error(fmt::format("{}: '#! {} = {}' is not a number", o.measurement, key, it->second));
  }
}

// A measured curve reduced with the same definitions as the runs, on the lab's geometry (default:
// the seed's, span 180 mm). Its strength, not its force, is the target: the simulated span may
// differ from the lab's, and sigma_b (eq. 15) is the material's figure.
void aim_at_measurement(const CalibrateCliOptions& o, CalibrationAims& aims) {
  const auto curve = bending::read_curve_csv(o.measurement);
  const auto meta = bending::read_curve_metadata(o.measurement);
  const bending::BendingGeometry lab{1e-3 * metadata_number(o, meta, "span_mm", o.lab_span_mm),
                                     1e-3 * metadata_number(o, meta, "pin_distance_mm", 80.0),
                                     1e-3 * metadata_number(o, meta, "width_mm", 30.0),
                                     1e-3 * metadata_number(o, meta, "height_mm", 35.0)};
  lab.check();
  if (const auto it = meta.find("displacement"); it != meta.end() && it->second != o.modulus)
    throw std::runtime_error(fmt::format("{}: its displacement column is '{}' but --modulus is '{}': the simulated E "
                                         "would not measure the same thing (use --modulus {})",
                                         o.measurement, it->second, o.modulus, it->second));
  const auto a = bending::analyse_curve(curve.displacement, curve.force, lab, o.geometry.analysis.curve);
  if (!o.target_e_given) aims.targets.youngs_modulus = a.youngs_modulus;
  aims.strength = a.flexural_strength;
  fmt::print("measurement {}: E = {:.4g} MPa (eq. 14, span {:.0f} mm), F_max = {:.4g} N, sigma_b = {:.4g} MPa, "
             "w_s,max = {:.3f} mm\n",
             o.measurement, 1e-6 * a.youngs_modulus, 1e3 * lab.span, a.force_max, 1e-6 * a.flexural_strength,
             1e3 * a.deflection_at_peak);
}

CalibrationAims calibration_aims(const CalibrateCliOptions& o) {
  CalibrationAims aims;
  aims.targets.youngs_modulus = o.target_e;
  aims.targets.tolerance = o.tolerance;
  aims.targets.max_runs = o.max_runs;
  if (!o.measurement.empty())
    aim_at_measurement(o, aims);
  else if (o.target_fmax > 0)
    aims.targets.force_max = o.target_fmax;
  else if (o.target_strength > 0)
    aims.strength = o.target_strength;
  return aims;
}

// One calibration run: the scene at the bond's parameters, analysed as a bending test. Stiffness
// runs (no breakage) stop once past the elastic part.
class CalibrationRunner {
 public:
  CalibrationRunner(const CalibrateCliOptions& o, const CommandContext& ctx, CalibrationAims& aims)
      : o_(o), ctx_(ctx), aims_(aims), log_(o.out_dir / "calibration.log") {}

  bending::CalibrationRun operator()(double eb, double sc, bool breakage, const std::string& stage, int index) {
    const RunSummary s = run_scene(options(eb, sc, breakage, stage, index), log_);
    auto report = analyse(s, breakage);
    if (aims_.strength && !aims_.targets.force_max) {
      aims_.targets.force_max = bending::force_from_flexural_stress(report.geometry, *aims_.strength);
      fmt::print("target strength {:.4g} MPa -> F_max = {:.4g} N (eq. 15, {:.0f} x {:.0f} x {:.0f} mm, span {:.0f} mm)\n",
                 1e-6 * *aims_.strength, *aims_.targets.force_max, 1e3 * report.length, 1e3 * report.geometry.width,
                 1e3 * report.geometry.height, 1e3 * report.geometry.span);
      if (!breakage) report = analyse(s, breakage);
    }
    io::write_json(beside(s.output, "_bending.json"), bending::report_json(report));
    const bool local = o_.modulus == "local";
    if (local && !report.gauges.valid)
      throw std::runtime_error(fmt::format(
          "calibration run {}: {}: only {} frames in the stiffness fit window, too few for the local instrumentation; "
          "record frames more often (--set output.frame_interval=...) or use --modulus pins",
          index, s.output.string(), report.gauges.fit_frames));
    bending::CalibrationRun c;
    c.youngs_modulus = local ? report.gauges.youngs_modulus : report.analysis.youngs_modulus;
    c.force_max = report.analysis.force_max;
    c.failed = report.analysis.failed;
    c.wall_seconds = s.wall_seconds;
    c.output = s.output.string();
    if (stiffness_stop_ == 0 && aims_.targets.force_max && report.analysis.stiffness > 0)
      // Later stiffness runs only need the elastic part: stop at the pin travel that reaches a
      // fraction of the target F_max at this run's pin stiffness (plus the contact onset).
      stiffness_stop_ = report.analysis.onset + o_.stiffness_fraction * *aims_.targets.force_max / report.analysis.stiffness;
    return c;
  }

 private:
  RunOptions options(double eb, double sc, bool breakage, const std::string& stage, int index) const {
    RunOptions run;
    run.scene = o_.scene;
    run.overrides = parse_overrides(o_.overrides);
    run.overrides.push_back({"bond.youngs_modulus", significant(eb, 9)});
    run.overrides.push_back({"bond.critical_stress", significant(sc, 9)});
    run.overrides.push_back({"simulation.breakage", breakage});
    if (!breakage && stiffness_stop_ > 0) run.overrides.push_back({"stop.max_displacement", significant(stiffness_stop_, 9)});
    run.out_dir = o_.out_dir / fmt::format("run_{:02d}_{}", index, stage);
    run.plugin_dirs = ctx_.plugin_dirs;
    run.threads = o_.threads;
    run.quiet = true;
    return run;
  }
  // Stiffness runs stop before failure: their fit window is taken on the target F_max.
  bending::BendingReport analyse(const RunSummary& s, bool breakage) const {
    bending::BendingOptions options = o_.geometry.analysis;
    if (!breakage && aims_.targets.force_max) options.curve.reference_force = *aims_.targets.force_max;
    return bending::analyse_bending_run(s.output, options);
  }

  const CalibrateCliOptions& o_;
  const CommandContext& ctx_;
  CalibrationAims& aims_;
  std::ofstream log_;
  double stiffness_stop_ = 0;  // m, pin travel of the stiffness runs
};

// Each run as it ends: a line on the terminal and a row of calibration_runs.csv, flushed.
class CalibrationProgress {
 public:
  CalibrationProgress(const std::filesystem::path& out_dir, const CalibrationAims& aims)
      : aims_(aims), csv_(out_dir / "calibration_runs.csv") {
    csv_ << "run,stage,bond_youngs_modulus_Pa,bond_critical_stress_Pa,breakage,youngs_modulus_Pa,force_max_N,failed,"
            "wall_seconds\n";
  }
  void operator()(const bending::CalibrationRun& c) {
    const auto& t = aims_.targets;
    fmt::print("run {:2d} {:<9} E_b = {:9.4g} MPa  sigma_crit = {:7.4g} MPa  ->  E = {:7.4g} MPa ({:+.1f} %)  F_max = {:7.4g} N{}  "
               "{:.0f} s\n",
               c.index, c.stage, 1e-6 * c.bond_youngs_modulus, 1e-6 * c.bond_critical_stress, 1e-6 * c.youngs_modulus,
               100 * (c.youngs_modulus / t.youngs_modulus - 1), c.force_max,
               t.force_max ? fmt::format(" ({:+.1f} %)", 100 * (c.force_max / *t.force_max - 1)) : "", c.wall_seconds);
    std::fflush(stdout);
    csv_ << fmt::format("{},{},{:.9g},{:.9g},{},{:.9g},{:.9g},{},{:.3f}\n", c.index, c.stage, c.bond_youngs_modulus,
                        c.bond_critical_stress, c.breakage, c.youngs_modulus, c.force_max, c.failed, c.wall_seconds);
    csv_.flush();
  }

 private:
  const CalibrationAims& aims_;
  std::ofstream csv_;
};

int calibrate_command(CalibrateCliOptions& o, const CommandContext& ctx) {
  apply_geometry(o.geometry);
  if (o.modulus != "local" && o.modulus != "pins")
    throw std::runtime_error(fmt::format("--modulus {}: expected local (the beam's own deflection under the pins, as "
                                         "local instrumentation measures it) or pins (the pin travel)", o.modulus));
  prepare_output_folder(o.out_dir, "--out");
  PluginHost host;
  load_plugins(host, ctx.plugin_dirs, std::cerr);
  auto [e_b, sigma] = scene_bond_parameters(o, host);
  CalibrationAims aims = calibration_aims(o);
  CalibrationRunner evaluate(o, ctx, aims);
  CalibrationProgress observer(o.out_dir, aims);
  const auto& t = aims.targets;
  fmt::print("calibrating {}: target E ({}) = {:.4g} MPa{}, tolerance {:.1f} %, at most {} runs; output in {}\n",
             o.scene.string(), o.modulus == "local" ? "eq. 14 on the beam's own deflection" : "eq. 14 on the pin travel",
             1e-6 * t.youngs_modulus,
             t.force_max      ? fmt::format(", F_max = {:.4g} N", *t.force_max)
             : aims.strength ? fmt::format(", sigma_b = {:.4g} MPa", 1e-6 * *aims.strength)
                              : std::string(", no strength target"),
             100 * t.tolerance, t.max_runs, o.out_dir.string());
  const auto result = bending::calibrate(aims.targets, e_b, sigma, std::ref(evaluate), std::ref(observer));
  write_text(o.out_dir / "calibration.csv", bending::calibration_csv(result));
  io::write_json(o.out_dir / "calibration.json", bending::calibration_json(result, aims.targets));
  fmt::print("{}: {}\nfinal: bond.youngs_modulus = {:.6g} Pa, bond.critical_stress = {:.6g} Pa\n",
             result.converged ? "converged" : "NOT converged", result.message, result.bond_youngs_modulus,
             result.bond_critical_stress);
  fmt::print("iterations: {}, {}\n", (o.out_dir / "calibration.csv").string(), (o.out_dir / "calibration.json").string());
  return result.converged ? 0 : 2;
}

}  // namespace

void add_bending_command(CLI::App& app, CommandContext& ctx) {
  auto bo = std::make_shared<BendingCliOptions>();
  auto* b = app.add_subcommand("bending", "four-point bending report of a run: E (eq. 14), F_max, sigma_b (eq. 15), "
                                          "crack position, fragments, quasi-static check, plot");
  b->add_option("run_file", bo->run, "run.h5 of a four-point bending scene")->required()->check(CLI::ExistingFile);
  b->add_option("--plot", bo->plot, "force-displacement figure (.png or .svg; default <run>_bending.png)");
  b->add_flag("--no-plot", bo->no_plot, "skip the figure");
  b->add_option("--json", bo->json, "report as JSON (default <run>_bending.json)");
  b->add_option("--crack-window", bo->analysis.crack_window, "crack cluster width in m (default: 2 mean diameters)");
  b->add_option("--gauge-section", bo->analysis.gauge_section,
                "local instrumentation: section width along the beam in m (default: 2 mean diameters)");
  b->add_option("--gauge-core", bo->analysis.gauge_core,
                "local instrumentation: height band around mid-height in m (default: half the height)");
  b->add_option("--local-damage-limit", bo->analysis.local_damage_limit,
                "local instrumentation: a frame counts as elastic while at most this fraction of the bonds has broken "
                "(default 0: before the first break; e.g. 1e-3 on a beam of 1e6 bonds)")
      ->check(CLI::Range(0.0, 0.05));
  add_geometry_options(*b, *bo);
  b->callback([bo, &ctx] { ctx.exit_code = bending_command(*bo); });

  auto co = std::make_shared<CalibrateCliOptions>();
  auto* c = app.add_subcommand("calibrate", "tune bond.youngs_modulus (breakage off) until E matches, then "
                                            "bond.critical_stress until F_max matches (seed sec. V)");
  c->footer("With --with EFFECT this is the measurement loop's calibration: shard calibrate MEASUREMENTS --scene S "
            "--with EFFECT [--param KEY ...] runs calibrate-effect (see its --help).");
  c->add_option("scene", co->scene, "four-point bending scene .toml")->required()->check(CLI::ExistingFile);
  c->add_option("--set", co->overrides, "scene overrides applied to every run");
  c->add_option("--out", co->out_dir, "output folder (default ./calibration)");
  auto* te = c->add_option("--target-E", co->target_e, "target Young's modulus in Pa (default 13.2e6, the seed; with "
                                                       "--measurement: the file's E unless given)");
  auto* ts = c->add_option("--target-strength", co->target_strength, "target flexural strength sigma_b in Pa (eq. 15)");
  auto* tf = c->add_option("--target-Fmax", co->target_fmax, "target peak force in N");
  auto* tm = c->add_option("--measurement", co->measurement, "measured curve CSV: E and F_max targets from it");
  ts->excludes(tf)->excludes(tm);
  tf->excludes(tm);
  c->add_option("--lab-span", co->lab_span_mm, "span of the measured specimen in mm (default: the file's '#! span_mm', "
                                               "else 180, the seed)");
  c->add_option("--modulus", co->modulus, "E to match: local (eq. 14 on the beam's own deflection under the pins, the "
                                          "seed's local instrumentation; default) or pins (eq. 14 on the pin travel)");
  c->add_option("--tolerance", co->tolerance, "relative tolerance on E and F_max (default 0.03)")
      ->check(number_from(0, true, "a positive fraction, e.g. 0.03 for 3 %"));
  c->add_option("--max-runs", co->max_runs, "give up after this many runs (default 20)")
      ->check(number_from(1, false, "at least 1 run"));
  c->add_option("--threads", co->threads, "OpenMP threads per run")->check(thread_count());
  add_geometry_options(*c, co->geometry);
  c->callback([co, te, &ctx] {
    co->target_e_given = te->count() > 0;
    ctx.exit_code = calibrate_command(*co, ctx);
  });

  add_bending_rate_check_command(app, ctx);
}

}  // namespace shard
