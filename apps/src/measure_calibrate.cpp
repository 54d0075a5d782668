// `shard calibrate-effect`: binds the options, fits one library effect with chosen base parameters
// to one measurement set (shard/measure/effect_calibration.hpp) on the DEM ensemble, and renders
// the fit: calibrate.md, calibrate.json, before/after plots per loading rate and a model version
// in the history.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "measure_commands.hpp"
#include "measure_plan.hpp"
#include "option_checks.hpp"
#include "model_history.hpp"
#include "shard/app/commands.hpp"
#include "shard/driver/output_folder.hpp"
#include "shard/io/json.hpp"
#include "shard/measure/effect_calibration.hpp"
#include "shard/measure/report.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

// calibrate.json's format (single-set form): raise it when a key changes meaning or disappears.
constexpr int kCalibrationFormatVersion = 1;

std::string effect_name(const EffectCalibration& fit) { return fit.effect ? fit.effect->name : std::string(); }

// One figure per loading rate: before.png, after.png (the slowest), then before@<rate>.png.
void plot_fit(const EffectCalibration& fit, const fs::path& out) {
  for (std::size_t k = 0; k < fit.before.at.size(); ++k) {
    const std::string suffix = k == 0 ? "" : fmt::format("@{:g}", fit.before.rates[k]);
    plot_comparison(fit.before.at[k], out / ("before" + suffix + ".png"),
                    fmt::format("before: base model ({:g} m/s)", fit.before.rates[k]));
    plot_comparison(fit.after.at[k], out / ("after" + suffix + ".png"),
                    fmt::format("after: {} ({:g} m/s)", fit.effect ? fit.effect->name : "base refit", fit.after.rates[k]));
  }
}

// Every rate in the entry (regimes and features "<name>@<rate>" when there are several).
void record_history(const EffectCalibration& fit, const std::string& label, const fs::path& work_dir) {
  HistoryEntry h = history_entry(
      "calibrate-effect", label.empty() ? (fit.effect ? "+ " + fit.effect->name : "base refit") : label, fit.after);
  h.chi_square = fit.chi_square_after;
  if (fit.effect) h.effects.push_back(fit.effect->name);
  for (std::size_t i = 0; i < fit.keys.size(); ++i) h.parameters[fit.keys[i]] = fit.fitted(i);
  if (fit.effect) h.parameters[fit.effect->parameter] = fit.effect_value();
  append_history(work_dir, h);
}

std::string credit_markdown(const EffectCalibration& fit) {
  if (!fit.base_only) return "";
  const CandidateEffect& e = *fit.effect;
  std::string md = fmt::format("Credit: of the chi^2 drop {:.1f}, the fitted base parameters with {} off make {:.1f} "
                               "(chi^2 {:.1f}, NRMSE {:.1f} %), {} at {} the remaining {:.1f} (p = {:.2g}). ",
                               fit.credit.total, e.name, fit.credit.by_base, *fit.chi_square_base_only,
                               100 * fit.base_only->nrmse(), e.name, e.sized(fit.effect_value()), fit.credit.by_effect,
                               fit.credit.effect_p);
  return md + (fit.credit.effect_supported
                   ? "The effect earns its parameter.\n\n"
                   : fmt::format("The gain is the base parameters': {}'s own share does not beat the penalty of its "
                                 "parameter (2) at p < 0.05, so these data do not support it.\n\n",
                                 e.name));
}

std::string bounds_markdown(const EffectCalibration& fit) {
  std::string md;
  for (std::size_t i = 0; i < fit.keys.size(); ++i)
    if (fit.base_at_bound(i) != RangeEnd::None)
      md += fmt::format("At bound: {} at {:.3g} x its start (the fit's range is {:g}-{:g} x): the base cannot absorb "
                        "this within it; start from a recalibrated base (--set {}=...).\n\n",
                        fit.keys[i], fit.best[i], fit.lower[i], fit.upper[i], fit.keys[i]);
  const RangeEnd end = fit.effect_at_bound();
  if (end != RangeEnd::None)
    md += fmt::format("At bound: {} at {} ({} of its range, {:g}-{:g} plausible sizes from neutral within "
                      "[min, max]).\n\n",
                      fit.effect->name, fit.effect->sized(fit.effect_value()),
                      end == RangeEnd::Lower ? "the lower end" : "the upper end", fit.lower.back(), fit.upper.back());
  return md;
}

std::string parameters_markdown(const EffectCalibration& fit, double time_compression) {
  std::string md = "| parameter | start | fitted |\n|---|---|---|\n";
  for (std::size_t i = 0; i < fit.keys.size(); ++i)
    md += fmt::format("| {} | {:.5g} | {:.5g} |\n", fit.keys[i], fit.start[i], fit.fitted(i));
  if (fit.effect)
    md += fmt::format("| {} ({}) | {:.5g} (neutral) | {:.5g}{} |\n", fit.effect->parameter, fit.effect->name,
                      fit.effect->neutral, fit.effect_value(), fit.effect->unit_suffix());
  if (time_compression != 1)
    md += fmt::format("\nSimulated at {0:g} x the measured loading rates (--time-compression): the fitted times are "
                      "model times; in the lab a bond.viscosity_time is {0:g} x the fitted value.\n",
                      time_compression);
  return md;
}

// Each regime's mean residual before and after, named "<regime>@<rate>" when there are several rates.
std::vector<std::pair<std::string, std::pair<double, double>>> regime_residuals(const EffectCalibration& fit) {
  std::vector<std::pair<std::string, std::pair<double, double>>> out;
  for (std::size_t k = 0; k < fit.before.at.size(); ++k)
    for (std::size_t r = 0; r < kRegimeCount; ++r) {
      const auto& b = fit.before.at[k].regimes[r];
      const auto& a = fit.after.at[k].regimes[r];
      if (b.points() == 0 || a.points() == 0) continue;
      const std::string name = fit.before.at.size() > 1 ? fmt::format("{}@{:g}", regime_name(b.regime), fit.before.rates[k])
                                                        : std::string(regime_name(b.regime));
      out.push_back({name, {b.mean_residual, a.mean_residual}});
    }
  return out;
}

std::string calibration_markdown(const EffectCalibration& fit, double time_compression) {
  const std::string name = effect_name(fit);
  std::string md = fmt::format("# calibrate-effect {}\n\n{} evaluations ({}); chi^2 {:.1f} -> {:.1f}; NRMSE {:.1f} % -> "
                               "{:.1f} %\n\n",
                               name.empty() ? "(base parameters only)" : name, fit.evaluations, fit.stop,
                               fit.chi_square_before, fit.chi_square_after, 100 * fit.before.nrmse(),
                               100 * fit.after.nrmse());
  if (fit.after.nrmse() > fit.before.nrmse())
    md += fmt::format("The NRMSE rose ({:.1f} % -> {:.1f} %) although chi^2 fell: the fitted model is not closer to the "
                      "measured curves; do not adopt it.\n\n",
                      100 * fit.before.nrmse(), 100 * fit.after.nrmse());
  md += credit_markdown(fit) + bounds_markdown(fit) + parameters_markdown(fit, time_compression);
  md += "\n| regime | mean residual before | after |\n|---|---|---|\n";
  for (const auto& [regime, residuals] : regime_residuals(fit))
    md += fmt::format("| {} | {:+.2f} | {:+.2f} |\n", regime, residuals.first, residuals.second);
  for (std::size_t k = 0; k < fit.after.at.size(); ++k)
    md += fmt::format("\nVerdict after{}: {}\n", fit.after.at.size() > 1 ? fmt::format(" at {:g} m/s", fit.after.rates[k]) : "",
                      fit.after.at[k].verdict);
  if (!fit.health.dynamic_warning.empty()) md += fmt::format("\n**Warning.** {}.\n", fit.health.dynamic_warning);
  return md;
}

io::Json calibration_json(const EffectCalibration& fit) {
  io::Json regimes = io::Json::object();
  for (const auto& [regime, residuals] : regime_residuals(fit)) regimes[regime] = {residuals.first, residuals.second};
  io::Json json = io::json_document(kCalibrationFormatVersion);
  json["effect"] = effect_name(fit);
  json["value"] = fit.effect_value();
  json["nrmse_before"] = fit.before.nrmse();
  json["nrmse_after"] = fit.after.nrmse();
  json["chi_square_before"] = fit.chi_square_before;
  json["chi_square_after"] = fit.chi_square_after;
  json["evaluations"] = fit.evaluations;
  json["regimes"] = std::move(regimes);
  json["chi_square_base_only"] = fit.chi_square_base_only ? io::Json(*fit.chi_square_base_only) : io::Json();
  json["gain_by_base"] = fit.credit.by_base;
  json["gain_by_effect"] = fit.credit.by_effect;
  json["effect_supported"] = fit.credit.effect_supported;
  json["dynamic_warning"] = fit.health.dynamic_warning;
  return json;
}

}  // namespace

void add_calibrate_effect_command(CLI::App& app, CommandContext& ctx) {
  struct Options {
    fs::path measurements, out = "calibrate", library;
    double rate = 0;
    ModelPlan model;
    SimulationOptions sim;
    std::vector<std::string> params;
    std::string effect;
    int max_evaluations = 16;
    std::string label;
    std::string scoring = "own";
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("calibrate-effect",
                                 "add a library effect to the model and fit its size with chosen base parameters (NLopt BOBYQA)");
  cmd->add_option("measurements", o->measurements, "measurement folder")->required();
  add_simulation_options(cmd, o->model, o->sim);
  cmd->get_option("--scene")->required();
  cmd->add_option("--with", o->effect, "effect name from the library (none: refit the base parameters only)");
  cmd->add_option("--param", o->params, "base parameter section.key fitted along (value read from the scene)");
  cmd->add_option("--effects", o->library, "candidate-effect library (default: effects.toml next to the scene)");
  cmd->add_option("--rate", o->rate, "loading rate to use (m/s)");
  cmd->add_option("--max-evaluations", o->max_evaluations, "objective evaluations (each is one run per seed)")
      ->check(number_from(1, false, "at least 1 evaluation"));
  cmd->add_option("--scoring", o->scoring,
                  "how the fit is scored: own (each model's band), frozen (the base model's band) or likelihood (own "
                  "band plus the Gaussian log-variance term)");
  cmd->add_option("--label", o->label, "name of the new model version in the history");
  cmd->add_option("--out", o->out, "folder for calibrate.md, calibrate.json and compare plots");
  cmd->callback([o, &ctx] {
    const MeasurementSet set = read_measurements(o->measurements);
    const MeasuredRates data{rate_groups(set, o->rate), set.metadata, compare_options(o->sim)};
    prepare_output_folder(o->out, "--out");  // after the cheap reads, before the simulations
    const fs::path library = o->library.empty() ? o->model.scene.parent_path() / "effects.toml" : o->library;
    std::optional<CandidateEffect> effect;
    if (!o->effect.empty()) effect = select_effects(read_effect_library(library), {o->effect}).front();
    const EffectCalibrationOptions options{o->params, o->max_evaluations, scoring_from_name(o->scoring)};
    EnsembleSimulator simulator(o->sim, ctx.plugin_dirs);
    const EffectCalibration fit = calibrate_effect(simulator, data, o->model, effect, options, std::cerr);
    plot_fit(fit, o->out);
    record_history(fit, o->label, o->sim.work_dir);
    const std::string md = calibration_markdown(fit, o->sim.time_compression);
    std::ofstream(o->out / "calibrate.md") << md;
    io::write_json(o->out / "calibrate.json", calibration_json(fit));
    fmt::print("{}", md);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
