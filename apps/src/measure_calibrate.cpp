// `shard calibrate-effect`: adds one library effect to the model and fits its parameter together
// with chosen base parameters to the measurements (NLopt BOBYQA, derivative-free: each objective
// value is a set of simulations). Objective: chi^2 of the standardised residual vector (regime
// means and feature scores), on fixed packing seeds so that it is a deterministic function.
// Start: the linearised refit (the runs `shard diagnose` made are cached and cost nothing).
// Every evaluation is scored against the base model's simulated band (frozen), so a size whose
// replicates scatter more cannot lower chi^2 by widening the band; the report says when the NRMSE
// rose all the same, and how much of the gain the base parameters made without the effect.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlopt.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "diagnosis_step.hpp"
#include "measure_commands.hpp"
#include "measure_plan.hpp"
#include "option_checks.hpp"
#include "shard/driver/output_folder.hpp"
#include "shard/io/json.hpp"
#include "shard/app/commands.hpp"
#include "shard/measure/confirmation.hpp"
#include "shard/measure/report.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

// calibrate.json's format (single-set form): raise it when a key changes meaning or disappears.
constexpr int kCalibrationFormatVersion = 1;

struct Fit {
  std::vector<std::string> keys;
  std::vector<double> base_values;
  const CandidateEffect* effect = nullptr;
  EnsembleSimulator* simulator = nullptr;
  const RateGroups* measured = nullptr;
  const Metadata* metadata = nullptr;
  const RateComparison* band = nullptr;  // the base model's: every evaluation is scored against it
  Scoring scoring = Scoring::Own;
  ModelPlan base;
  int evaluations = 0;
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_x;

  // x: base parameters relative to their start values, then the effect in units of its
  // plausible size above neutral.
  ModelPlan model(const std::vector<double>& x) const {
    std::vector<double> v;
    for (std::size_t i = 0; i < keys.size(); ++i) v.push_back(base_values[i] * x[i]);
    ModelPlan m = with_parameters(base, keys, v);
    if (effect) m = with_effect(m, *effect, value_of(x));
    return m;
  }
  RateComparison evaluate(const std::vector<double>& x) const {
    return simulate_and_compare(*simulator, *measured, *metadata, {model(x)}, std::cerr).front();
  }
  double value_of(const std::vector<double>& x) const {
    return effect->value_at(x.back());
  }
  double objective(const std::vector<double>& x) {
    const double chi2 = model_score(evaluate(x), *band, scoring);
    ++evaluations;
    fmt::print(stderr, "calibrate-effect: evaluation {} chi^2 {:.2f}\n", evaluations, chi2);
    if (chi2 < best) best = chi2, best_x = x;
    return chi2;
  }
};

double nlopt_objective(unsigned n, const double* x, double* grad, void* data) {
  (void)grad;  // derivative-free
  return static_cast<Fit*>(data)->objective(std::vector<double>(x, x + n));
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
    const RateGroups measured = rate_groups(set, o->rate);
    prepare_output_folder(o->out, "--out");  // after the cheap reads, before the simulations
    const fs::path library = o->library.empty() ? o->model.scene.parent_path() / "effects.toml" : o->library;
    if (o->params.empty() && o->effect.empty())
      throw std::runtime_error("calibrate-effect: give --with EFFECT and/or --param");
    std::vector<CandidateEffect> effects;
    if (!o->effect.empty()) effects = select_effects(read_effect_library(library), {o->effect});
    Fit fit;
    fit.keys = o->params;
    fit.scoring = scoring_from_name(o->scoring);
    for (const auto& k : o->params) fit.base_values.push_back(scene_number(o->model, k));
    EnsembleSimulator simulator(o->sim, ctx.plugin_dirs);
    // The trial size as diagnose resolves it (the base run at the scene's values), so the
    // linearised start below is diagnose's first step, cached.
    std::string scaled;
    effects = plausible_on_base_run(std::move(effects), simulator, measured, set.metadata,
                                    step_plan(o->model, o->params, StepModel{fit.base_values, {}}), scaled, std::cerr);
    fit.effect = effects.empty() ? nullptr : &effects.front();
    fit.simulator = &simulator;
    fit.measured = &measured;
    fit.metadata = &set.metadata;
    fit.base = o->model;

    // Linearised start: the first step of `shard diagnose` on the same runs, so its refit is cached.
    std::vector<const CandidateEffect*> candidates;
    for (const auto& e : effects) candidates.push_back(&e);
    const StepLinearisation lin = linearise_step(simulator, measured, set.metadata, o->model, o->params,
                                                 StepModel{fit.base_values, {}}, candidates, nullptr, fit.scoring, std::cerr);
    fit.band = &lin.base_comparison;
    const LinearRefit lr = linear_refit(lin.base.values, lin.jacobian, lin.signatures);
    const std::size_t n = fit.keys.size() + (fit.effect ? 1 : 0);
    std::vector<double> lower(n), upper(n), x(n);
    for (std::size_t i = 0; i < fit.keys.size(); ++i) {
      lower[i] = 0.5, upper[i] = 2.0;
      x[i] = clamp_base_factor(1 + lr.base_step[i]);
    }
    if (fit.effect) {
      // From neutral to four plausible sizes, inside the effect's physical range.
      lower.back() = std::max(0.0, fit.effect->scale_min());
      upper.back() = std::min(4.0, fit.effect->scale_max());
      x.back() = std::clamp(clamp_effect_scale(lr.effect_scale.front()), lower.back(), upper.back());
    }
    const RateComparison before = lin.base_comparison;
    nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(n));
    opt.set_lower_bounds(lower);
    opt.set_upper_bounds(upper);
    opt.set_min_objective(nlopt_objective, &fit);
    opt.set_maxeval(o->max_evaluations);
    opt.set_xtol_rel(1e-3);
    std::vector<double> step(n, 0.05);
    if (fit.effect) step.back() = 0.25;
    opt.set_initial_step(step);
    double minimum = 0;
    std::string stop = "converged";
    try {
      const auto result = opt.optimize(x, minimum);
      if (result == nlopt::MAXEVAL_REACHED) stop = "evaluation budget reached";
    } catch (const nlopt::roundoff_limited&) {
      stop = "round-off limited";
    } catch (const std::runtime_error& e) {
      // NLopt's generic NLOPT_FAILURE: BOBYQA's quadratic model can break down on an objective
      // with packing noise. Every evaluation so far is a finished simulation; keep the best one
      // rather than lose them. Anything else (a failed run) still ends the command.
      if (std::string_view(e.what()) != "nlopt failure" || fit.best_x.empty()) throw;
      stop = "BOBYQA stopped (its quadratic model broke down on the noisy objective); the best evaluation is kept";
    }
    const std::vector<double> best = fit.best_x.empty() ? x : fit.best_x;
    const ModelPlan final_model = fit.model(best);
    const RateComparison after = fit.evaluate(best);
    auto score = [&](const RateComparison& c) { return model_score(c, before, fit.scoring); };
    // Credit: the fitted base parameters with the effect switched off (one more run per seed).
    std::optional<RateComparison> base_only;
    GainCredit credit;
    if (fit.effect) {
      std::vector<double> off = best;
      off.back() = 0;  // value_at(0): neutral
      base_only = fit.evaluate(off);
      credit = credit_gain(score(before), score(*base_only), score(after));
    }

    // One figure per loading rate: before.png, after.png (the slowest), then before@<rate>.png.
    for (std::size_t k = 0; k < before.at.size(); ++k) {
      const std::string suffix = k == 0 ? "" : fmt::format("@{:g}", before.rates[k]);
      plot_comparison(before.at[k], o->out / ("before" + suffix + ".png"), fmt::format("before: base model ({:g} m/s)", before.rates[k]));
      plot_comparison(after.at[k], o->out / ("after" + suffix + ".png"),
                      fmt::format("after: {} ({:g} m/s)", o->effect.empty() ? "base refit" : o->effect, after.rates[k]));
    }
    // Every rate in the entry (regimes and features "<name>@<rate>" when there are several).
    HistoryEntry h = history_entry("calibrate-effect", o->label.empty() ? (o->effect.empty() ? "base refit" : "+ " + o->effect) : o->label, after);
    h.chi_square = score(after);
    if (fit.effect) h.effects.push_back(fit.effect->name);
    for (std::size_t i = 0; i < fit.keys.size(); ++i) h.parameters[fit.keys[i]] = fit.base_values[i] * best[i];
    if (fit.effect) h.parameters[fit.effect->parameter] = fit.value_of(best);
    append_history(o->sim.work_dir, h);

    std::string md = fmt::format("# calibrate-effect {}\n\n{} evaluations ({}); chi^2 {:.1f} -> {:.1f}; NRMSE {:.1f} % -> {:.1f} %\n\n",
                                 o->effect.empty() ? "(base parameters only)" : o->effect, fit.evaluations, stop,
                                 score(before), score(after), 100 * before.nrmse(), 100 * after.nrmse());
    if (after.nrmse() > before.nrmse())
      md += fmt::format("The NRMSE rose ({:.1f} % -> {:.1f} %) although chi^2 fell: the fitted model is not closer to the "
                        "measured curves; do not adopt it.\n\n",
                        100 * before.nrmse(), 100 * after.nrmse());
    if (base_only) {
      md += fmt::format("Credit: of the chi^2 drop {:.1f}, the fitted base parameters with {} off make {:.1f} (chi^2 {:.1f}, "
                        "NRMSE {:.1f} %), {} at {:.4g} {} the remaining {:.1f} (p = {:.2g}). ",
                        credit.total, fit.effect->name, credit.by_base, score(*base_only), 100 * base_only->nrmse(),
                        fit.effect->name, fit.value_of(best), fit.effect->unit, credit.by_effect, credit.effect_p);
      md += credit.effect_supported
                ? "The effect earns its parameter.\n\n"
                : fmt::format("The gain is the base parameters': {}'s own share does not beat the penalty of its parameter "
                              "(2) at p < 0.05, so these data do not support it.\n\n",
                              fit.effect->name);
    }
    for (std::size_t i = 0; i < fit.keys.size(); ++i)
      if (best[i] <= lower[i] * (1 + 1e-6) || best[i] >= upper[i] * (1 - 1e-6))
        md += fmt::format("At bound: {} at {:.3g} x its start (the fit's range is {:g}-{:g} x): the base cannot absorb this "
                          "within it; start from a recalibrated base (--set {}=...).\n\n",
                          fit.keys[i], best[i], lower[i], upper[i], fit.keys[i]);
    if (fit.effect && (best.back() <= lower.back() + 1e-6 || best.back() >= upper.back() - 1e-6))
      md += fmt::format("At bound: {} at {:.4g} {} ({} of its range, {:g}-{:g} plausible sizes from neutral within "
                        "[min, max]).\n\n",
                        fit.effect->name, fit.value_of(best), fit.effect->unit,
                        best.back() <= lower.back() + 1e-6 ? "the lower end" : "the upper end", lower.back(), upper.back());
    md += "| parameter | start | fitted |\n|---|---|---|\n";
    for (std::size_t i = 0; i < fit.keys.size(); ++i)
      md += fmt::format("| {} | {:.5g} | {:.5g} |\n", fit.keys[i], fit.base_values[i], fit.base_values[i] * best[i]);
    if (fit.effect)
      md += fmt::format("| {} ({}) | {:.5g} (neutral) | {:.5g} {} |\n", fit.effect->parameter, fit.effect->name,
                        fit.effect->neutral, fit.value_of(best), fit.effect->unit);
    if (o->sim.time_compression != 1)
      md += fmt::format("\nSimulated at {0:g} x the measured loading rates (--time-compression): the fitted times are "
                        "model times; in the lab a bond.viscosity_time is {0:g} x the fitted value.\n",
                        o->sim.time_compression);
    md += "\n| regime | mean residual before | after |\n|---|---|---|\n";
    io::Json json_regimes = io::Json::object();
    for (std::size_t k = 0; k < before.at.size(); ++k)
      for (std::size_t r = 0; r < kRegimeCount; ++r) {
        const auto& b = before.at[k].regimes[r];
        const auto& a = after.at[k].regimes[r];
        if (b.points() == 0 || a.points() == 0) continue;
        const std::string name = before.at.size() > 1 ? fmt::format("{}@{:g}", regime_name(b.regime), before.rates[k])
                                                      : std::string(regime_name(b.regime));
        md += fmt::format("| {} | {:+.2f} | {:+.2f} |\n", name, b.mean_residual, a.mean_residual);
        json_regimes[name] = {b.mean_residual, a.mean_residual};
      }
    for (std::size_t k = 0; k < after.at.size(); ++k)
      md += fmt::format("\nVerdict after{}: {}\n", after.at.size() > 1 ? fmt::format(" at {:g} m/s", after.rates[k]) : "",
                        after.at[k].verdict);
    const std::string dynamic = simulator.dynamic_warning();
    if (!dynamic.empty()) md += fmt::format("\n**Warning.** {}.\n", dynamic);
    std::ofstream(o->out / "calibrate.md") << md;
    io::Json json = io::json_document(kCalibrationFormatVersion);
    json["effect"] = o->effect;
    json["value"] = fit.effect ? fit.value_of(best) : 0.0;
    json["nrmse_before"] = before.nrmse();
    json["nrmse_after"] = after.nrmse();
    json["chi_square_before"] = score(before);
    json["chi_square_after"] = score(after);
    json["evaluations"] = fit.evaluations;
    json["regimes"] = std::move(json_regimes);
    json["chi_square_base_only"] = base_only ? io::Json(score(*base_only)) : io::Json();
    json["gain_by_base"] = credit.by_base;
    json["gain_by_effect"] = credit.by_effect;
    json["effect_supported"] = credit.effect_supported;
    json["dynamic_warning"] = dynamic;
    io::write_json(o->out / "calibrate.json", json);
    fmt::print("{}", md);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
