// `shard diagnose`: which candidate effect explains what the calibrated base model misses.
// 1. One parallel batch on the model's packing seeds (common random numbers): the base, each
//    base parameter +5 % (the Jacobian), each library effect at its plausible size (signature).
// 2. Score test on the part of the residual the base parameters cannot absorb (diagnosis.hpp).
// 3. Confirmation: the base refit alone and the top effects refit with it (linear prediction of
//    the sizes) are simulated; the real drop in chi-square and the information criteria decide.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <iostream>
#include <memory>

#include "measure_commands.hpp"
#include "measure_plan.hpp"
#include "shard/app/commands.hpp"
#include "shard/measure/confirmation.hpp"
#include "shard/measure/report.hpp"
#include "shard/measure/statistics.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

struct Confirmation {
  std::string name;  // "base refit" or the effect
  std::vector<double> parameters;
  double effect_value = 0;
  double chi_square = 0, nrmse = 0, delta_aic = 0, delta_bic = 0;
  std::string failure;  // the refit's run failed: its first error line
};

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

}  // namespace

void add_diagnose_command(CLI::App& app, CommandContext& ctx) {
  struct Options {
    fs::path measurements, out = "diagnose", library;
    double rate = 0;
    ModelPlan model;
    SimulationOptions sim;
    std::vector<std::string> params;
    std::vector<std::string> only;
    int refit = 2;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("diagnose", "rank candidate effects by how much of the model's residual each explains");
  cmd->add_option("measurements", o->measurements, "measurement folder")->required();
  add_simulation_options(cmd, o->model, o->sim);
  cmd->get_option("--scene")->required();
  cmd->add_option("--rate", o->rate, "loading rate to use (m/s)");
  cmd->add_option("--param", o->params, "calibrated base parameter section.key (its value is read from the scene)")
      ->required();
  cmd->add_option("--effects", o->library, "candidate-effect library (default: effects.toml next to the scene)");
  cmd->add_option("--only", o->only, "try only these effects of the library (comma-separated)")->delimiter(',');
  cmd->add_option("--refit", o->refit, "effects confirmed by a refit run (0: none)");
  cmd->add_option("--out", o->out, "folder for diagnose.md and diagnose.json");
  cmd->callback([o, &ctx] {
    const MeasurementSet set = read_measurements(o->measurements);
    const RateGroups measured = rate_groups(set, o->rate);
    const fs::path library = o->library.empty() ? o->model.scene.parent_path() / "effects.toml" : o->library;
    const auto effects = select_effects(read_effect_library(library), o->only);
    std::vector<double> values;
    for (const auto& k : o->params) values.push_back(scene_number(o->model, k, ctx.plugin_dirs));
    Simulator simulator(o->sim, ctx.plugin_dirs);
    fmt::print(stderr, "diagnose: base, {} parameter steps and {} effects on {} packing seeds\n", o->params.size(),
               effects.size(), o->sim.seeds);
    const Linearisation lin = linearise(simulator, measured, set.metadata, o->model, o->params, values, effects, std::cerr);
    const Diagnosis d = diagnose(lin.base.names, lin.base.values, lin.jacobian, lin.signatures);
    const double m = static_cast<double>(lin.base.values.size());

    // Confirmation runs: base refit alone, then each of the top effects with the base refit.
    std::vector<Confirmation> confirmations;
    std::vector<ModelPlan> models;
    auto refit_model = [&](const std::vector<EffectSignature>& sig, const CandidateEffect* effect) {
      const LinearRefit lr = linear_refit(lin.base.values, lin.jacobian, sig);
      Confirmation c;
      c.name = effect ? effect->name : "base refit";
      for (std::size_t i = 0; i < values.size(); ++i) c.parameters.push_back(values[i] * clamp_base_factor(1 + lr.base_step[i]));
      ModelPlan plan = with_parameters(o->model, o->params, c.parameters);
      if (effect) {
        c.effect_value = effect->value_at(clamp_effect_scale(lr.effect_scale[0]));
        plan = with_effect(plan, *effect, c.effect_value);
      }
      confirmations.push_back(c);
      models.push_back(plan);
    };
    const auto tops = static_cast<std::size_t>(std::max(0, o->refit));
    if (tops > 0 && d.verdict != "adequate") {  // noise needs no refit: its runs would be wasted
      refit_model({}, nullptr);
      for (std::size_t k = 0; k < std::min(tops, d.ranking.size()); ++k)
        for (std::size_t e = 0; e < effects.size(); ++e)
          if (effects[e].name == d.ranking[k].name && d.ranking[k].score > 0) refit_model({lin.signatures[e]}, &effects[e]);
      // One batch; when a run fails (a linear step can reach an unstable size), the models are
      // retried one by one: finished runs are cached, and a failed effect refit is reported and
      // left out of the decision instead of ending the diagnosis.
      std::vector<RateComparison> sims;
      try {
        sims = simulate_and_compare(simulator, measured, set.metadata, models, std::cerr);
      } catch (const std::exception&) {
        sims.assign(models.size(), {});
        for (std::size_t k = 0; k < models.size(); ++k) try {
            sims[k] = simulate_and_compare(simulator, measured, set.metadata, {models[k]}, std::cerr).front();
          } catch (const std::exception& e) {
            if (k == 0) throw;  // without the base refit there is nothing to compare with
            const std::string what = e.what();
            confirmations[k].failure = what.substr(0, what.find('\n'));
          }
      }
      for (std::size_t k = 0; k < models.size(); ++k) {
        if (!confirmations[k].failure.empty()) {
          confirmations[k].chi_square = confirmations[k].nrmse = std::numeric_limits<double>::infinity();
          continue;
        }
        confirmations[k].chi_square = sims[k].chi_square();
        confirmations[k].nrmse = sims[k].nrmse();
        const double extra = k == 0 ? 0 : 1;
        confirmations[k].delta_aic = confirmations[k].chi_square - confirmations[0].chi_square + 2 * extra;
        confirmations[k].delta_bic = confirmations[k].chi_square - confirmations[0].chi_square + extra * std::log(m);
      }
    }
    // The score test ranks on the linearisation; the confirmation runs are the real refits, so
    // they decide (confirmation.hpp): an effect is named only when its refit explains most of the
    // structured excess, both information criteria prefer it and what remains is noise.
    std::string verdict = d.verdict;
    ConfirmationDecision decision;
    if (verdict != kAdequate && confirmations.size() > 1) {
      std::vector<RefitOutcome> refits;
      for (std::size_t k = 1; k < confirmations.size(); ++k) refits.push_back({confirmations[k].name, confirmations[k].chi_square});
      decision = decide_from_refits(confirmations[0].chi_square, refits, lin.base.values.size(), o->params.size());
      verdict = decision.verdict;
    }
    const bool confirmed = decision.best_partial.empty();

    std::string md = fmt::format("# Diagnosis: {}\n\nmeasurements {}, model {}, {} packing seeds, base parameters {}.\n",
                                 verdict, o->measurements.string(), o->model.scene.string(), o->sim.seeds, join(o->params));
    md += fmt::format("Residual chi^2 {:.1f} over {} components; after what the base parameters can absorb {:.1f} "
                      "(p = {:.3g} against chi^2({})); base NRMSE {:.1f} %.\n\n",
                      d.chi_square, lin.base.values.size(), d.chi_square_unabsorbed, d.p_value,
                      lin.base.values.size() - o->params.size(), 100 * lin.base_comparison.nrmse());
    if (verdict == kAdequate && confirmations.empty())
      md += "The residual left after the base parameters is compatible with noise: no effect is needed.\n\n";
    else if (verdict == kAdequate)
      md += fmt::format("The base parameters refitted (simulated, not predicted) leave chi^2 {:.1f} over {} degrees of "
                        "freedom, p = {:.2g}: compatible with noise, so no effect is needed. The score test's lead "
                        "({}, p = {:.2g}) was not borne out by the refits below; an effect too weak for these data "
                        "cannot be told from noise (more specimens or another rate would).\n\n",
                        confirmations[0].chi_square, lin.base.values.size() - o->params.size(), decision.base_p,
                        d.ranking.empty() ? "-" : d.ranking.front().name,
                        d.ranking.empty() ? 1.0 : d.ranking.front().p_value);
    else if (verdict == kUnexplained) {
      md += fmt::format("No candidate explains the structured residual: the missing physics is not in the library "
                        "({}).",
                        library.string());
      if (!confirmed)
        for (const auto& e : decision.effects)
          if (e.name == decision.best_partial)
            md += fmt::format(" The best refit, {}, explains {:.0f} % of the excess chi^2 over noise ({:.1f}) and "
                              "leaves p = {:.2g}: not enough to name it.",
                              e.name, 100 * e.share_explained, decision.excess, e.p_after);
      // Say what the data show that the base model does not, in the comparison's words, and how a
      // user adds the missing physics: the library is open.
      md += "\n\nWhat the base model misses:";
      for (std::size_t k = 0; k < lin.base_comparison.at.size(); ++k)
        md += fmt::format(" {}{}", lin.base_comparison.at.size() > 1 ? fmt::format("at {:g} m/s: ", lin.base_comparison.rates[k]) : "",
                          lin.base_comparison.at[k].verdict);
      md += " To add an effect: `shard new-plugin` writes a one-file plugin whose new parameter has a neutral value "
            "(docs/plugins.md); an [[effect]] entry for it in the library lets diagnose try it and `shard calibrate "
            "--with` fit it.";
      md += "\n\n";
    }
    md += "| effect | score (LM) | p-value | explains | absorbed by base | estimated value | dAIC | dBIC | regimes/features it explains |\n"
          "|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& s : d.ranking) {
      const CandidateEffect* e = nullptr;
      for (const auto& x : effects)
        if (x.name == s.name) e = &x;
      md += fmt::format("| {} | {:.2f} | {:.3g} | {:.0f} % | {:.0f} % | {:.4g} {}{} | {:+.1f} | {:+.1f} | {} |\n", s.name,
                        s.score, s.p_value, 100 * s.explained, 100 * s.absorbed, e->neutral + s.size, e->unit,
                        !s.at_bound ? "" : s.size == 0 ? " (the data ask for it reversed: outside its physical range)"
                                                       : " (clamped at its physical bound)",
                        s.delta_aic, s.delta_bic,
                        join(s.explains));
    }
    if (!confirmations.empty()) {
      md += fmt::format("\nConfirmation runs (simulated, not predicted; excess chi^2 of the base refit over its {} "
                        "degrees of freedom: {:.1f}):\n\n| model | chi^2 | NRMSE | dAIC vs base refit | dBIC | share of "
                        "excess | p after | p of the drop | values |\n|---|---|---|---|---|---|---|---|---|\n",
                        lin.base.values.size() - o->params.size(), decision.excess);
      for (std::size_t k = 0; k < confirmations.size(); ++k) {
        const auto& c = confirmations[k];
        const ConfirmedEffect* ce = k > 0 && k - 1 < decision.effects.size() ? &decision.effects[k - 1] : nullptr;
        std::string v;
        for (std::size_t i = 0; i < c.parameters.size(); ++i) v += fmt::format("{}{}={:.4g}", v.empty() ? "" : ", ", o->params[i], c.parameters[i]);
        if (c.name != "base refit") v += fmt::format(", {}={:.4g}", c.name, c.effect_value);
        if (!c.failure.empty()) {
          md += fmt::format("| {} | run failed | - | - | - | - | - | - | {} |\n", c.name, v);
          continue;
        }
        md += fmt::format("| {} | {:.1f} | {:.1f} % | {:+.1f} | {:+.1f} | {} | {} | {} | {} |\n", c.name, c.chi_square,
                          100 * c.nrmse, c.delta_aic, c.delta_bic, ce ? fmt::format("{:.0f} %", 100 * ce->share_explained) : "-",
                          ce ? fmt::format("{:.2g}", ce->p_after) : fmt::format("{:.2g}", decision.base_p),
                          ce ? fmt::format("{:.2g}", ce->p_drop) : "-", v);
      }
    }
    for (const auto& c : confirmations)
      if (!c.failure.empty())
        md += fmt::format("\nThe refit with {} did not run to the end and is left out: {}\n", c.name, c.failure);
    for (const auto& rival : decision.rivals) {
      std::string how;
      double rival_chi2 = 0, named_chi2 = 0;
      for (const auto& e : decision.effects) {
        if (e.name == rival) rival_chi2 = e.chi_square;
        if (e.name == verdict) named_chi2 = e.chi_square;
      }
      for (const auto& x : effects)
        if ((x.name == rival || x.name == verdict) && !x.separated_by.empty())
          how += fmt::format("{}{}: {}", how.empty() ? "" : "; ", x.name, x.separated_by);
      md += fmt::format("\n{}'s refit (chi^2 {:.1f}) explains these data almost as well as {}'s ({:.1f}; within {:g}): "
                        "they cannot tell the two apart. Measurements that would: {}.\n",
                        rival, rival_chi2, verdict, named_chi2, ConfirmationRule{}.rival_chi_square,
                        how.empty() ? "a second loading rate, an unloading cycle or fragment sizes" : how);
    }
    for (const auto& [a, b] : d.indistinguishable) {
      std::string how;
      for (const auto& x : effects)
        if ((x.name == a || x.name == b) && !x.separated_by.empty())
          how += fmt::format("{}{}: {}", how.empty() ? "" : "; ", x.name, x.separated_by);
      md += fmt::format("\n{} and {} have nearly parallel signatures here: these data cannot tell them apart. "
                        "Measurements that would: {}.\n",
                        a, b, how.empty() ? "a second loading rate, an unloading cycle or fragment sizes" : how);
    }
    for (const auto& s : d.ranking)
      if (s.absorbed > 0.9)
        md += fmt::format("\n{}: {:.0f} % of its signature is absorbed by the base parameters: a calibration of {} "
                          "alone would hide it.\n",
                          s.name, 100 * s.absorbed, join(o->params));
    md += fmt::format("\nLargest kinetic/elastic energy ratio of the runs before breakage: {:.2g}.\n",
                      simulator.max_kinetic_to_elastic());
    const std::string dynamic = simulator.dynamic_warning();
    if (!dynamic.empty()) md += fmt::format("\n**Warning.** {}.\n", dynamic);

    std::string json = fmt::format("{{\"verdict\": \"{}\", \"chi_square\": {:.9g}, \"chi_square_unabsorbed\": {:.9g}, "
                                   "\"p_value\": {:.9g}, \"nrmse\": {:.9g}, \"ranking\": [",
                                   json_escape(verdict), d.chi_square, d.chi_square_unabsorbed, d.p_value,
                                   lin.base_comparison.nrmse());
    for (std::size_t k = 0; k < d.ranking.size(); ++k) {
      const auto& s = d.ranking[k];
      const CandidateEffect* e = nullptr;
      for (const auto& x : effects)
        if (x.name == s.name) e = &x;
      json += fmt::format("{}{{\"name\": \"{}\", \"score\": {:.9g}, \"p_value\": {:.9g}, \"explained\": {:.9g}, "
                          "\"absorbed\": {:.9g}, \"value\": {:.9g}, \"at_bound\": {}}}",
                          k ? ", " : "", json_escape(s.name), s.score, s.p_value, s.explained, s.absorbed,
                          e->neutral + s.size, s.at_bound);
    }
    json += "], \"confirmations\": [";
    // JSON has no infinity: a refit that failed has null numbers and its error.
    auto number = [](double x) { return std::isfinite(x) ? fmt::format("{:.9g}", x) : std::string("null"); };
    for (std::size_t k = 0; k < confirmations.size(); ++k) {
      const ConfirmedEffect* ce = k > 0 && k - 1 < decision.effects.size() ? &decision.effects[k - 1] : nullptr;
      const auto& c = confirmations[k];
      json += fmt::format("{}{{\"name\": \"{}\", \"chi_square\": {}, \"nrmse\": {}, \"delta_aic\": {}, "
                          "\"delta_bic\": {}, \"share_explained\": {}, \"p_after\": {}, \"p_drop\": {}, \"value\": {:.9g}, "
                          "\"failure\": \"{}\"}}",
                          k ? ", " : "", json_escape(c.name), number(c.chi_square), number(c.nrmse),
                          number(c.delta_aic), number(c.delta_bic), number(ce ? ce->share_explained : 0.0),
                          number(ce ? ce->p_after : decision.base_p), number(ce ? ce->p_drop : 1.0), c.effect_value,
                          json_escape(c.failure));
    }
    std::string rivals;
    for (const auto& r : decision.rivals) rivals += fmt::format("{}\"{}\"", rivals.empty() ? "" : ", ", json_escape(r));
    json += fmt::format("], \"excess\": {:.9g}, \"partial\": \"{}\", \"rivals\": [{}], \"dynamic_warning\": \"{}\"}}\n",
                        decision.excess, json_escape(decision.best_partial), rivals, json_escape(dynamic));
    fs::create_directories(o->out);
    std::ofstream(o->out / "diagnose.md") << md;
    std::ofstream(o->out / "diagnose.json") << json;
    fmt::print("{}", md);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
