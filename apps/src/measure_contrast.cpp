// `shard diagnose SET_A SET_B ... [--reference SET]` (routed to diagnose-sets): which library
// effect makes each set differ from the reference (or from the consensus of the others), with
// the base model's form error cancelled in the difference (contrast_study.hpp,
// shard/measure/contrast.hpp). Steps:
// 1. the base parameters fitted to the reference on simulated runs; its form error reported;
// 2. one batch on common packing seeds: the base and each effect at its plausible size, at every
//    rate the sets were tested at; each set's measured contrast against the effects' simulated
//    contrasts (linear sizes, Hotelling's test for "no difference");
// 3. confirmation: the best effects of each set simulated at their fitted sizes (and once more at
//    the size their simulated contrast asks for); those runs decide;
// 4. two effects at once: where the closest single effect leaves a remainder beyond noise, it is
//    kept and the next sought as a pair with it (contrast_pairs.cpp).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "contrast_report.hpp"
#include "shard/driver/output_folder.hpp"
#include "contrast_study.hpp"
#include "measure_commands.hpp"
#include "shard/app/commands.hpp"
#include "shard/measure/report.hpp"
#include "significant_digits.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;
using namespace measure;

}  // namespace

void add_diagnose_sets_command(CLI::App& app, CommandContext& ctx) {
  auto o = std::make_shared<ContrastOptionsCli>();
  auto* cmd = app.add_subcommand("diagnose-sets", "which library effect makes each measurement set differ from the "
                                                  "reference (also: shard diagnose SET_A SET_B ...)");
  add_contrast_options(cmd, *o);
  cmd->add_option("--finer", o->finer,
                  "also fit the base at generator diameters this factor smaller (e.g. 0.8) and report whether the "
                  "form error shrinks with resolution")
      ->check(CLI::Range(0.2, 1.0));
  cmd->add_option("--confirm", o->confirm, "best effects per set confirmed by simulated runs at their fitted size");
  cmd->add_option("--pairs", o->pairs,
                  "pairs of effects simulated per set when the closest single effect leaves a remainder beyond "
                  "noise (two effects at once; 0: single effects only)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--pair-iterations", o->pair_iterations,
                  "runs per pair: the first at the linear sizes, later ones a Gauss-Newton step each")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", o->out, "folder for diagnose.md, diagnose.json and contrasts.png")->default_val("diagnose");
  cmd->callback([o, &ctx] {
    const ContrastSets sets = read_contrast_sets(o->sets, o->reference);
    const auto library = contrast_effects(*o);
    prepare_output_folder(o->out, "--out");  // after the cheap reads, before the simulations
    Simulator simulator(o->sim, ctx.plugin_dirs);
    ContrastStudy study(sets, simulator, o->model);
    const BaseCalibration cal = study.calibrate_base(o->params, o->params.empty() ? 0 : o->base_iterations, std::cerr,
                                                     ctx.plugin_dirs);
    // Does resolution explain the form error? The same base fit at a finer packing.
    std::optional<BaseCalibration> finer;
    if (o->finer > 0) {
      ModelPlan fine = o->model;
      for (const char* key : {"generator.diameter_min", "generator.diameter_max"})
        fine.overrides.push_back({key, significant(o->finer * scene_number(o->model, key), 9)});
      ContrastStudy fine_study(sets, simulator, fine);
      fmt::print(stderr, "diagnose: the base fit again with diameters x {:g}\n", o->finer);
      finer = fine_study.calibrate_base(o->params, o->params.empty() ? 0 : o->base_iterations, std::cerr,
                                                     ctx.plugin_dirs);
    }

    std::string scaled;
    const auto effects = scaled_to_base_run(library, study, scaled, std::cerr);
    std::vector<ModelPlan> models{study.base()};
    for (const auto& e : effects) {
      models.push_back(with_effect(study.base(), e, e.plausible));
      models.back().probe = true;
    }
    fmt::print(stderr, "diagnose: base and {} effects at {} rate(s) on {} packing seeds\n", effects.size(),
               study.rates().size(), o->sim.seeds);
    const auto sims = study.simulate(models, std::cerr);

    std::vector<SetDiagnosis> out;
    for (std::size_t s = 0; s < sets.sets.size(); ++s) {
      if (sets.reference && *sets.reference == s) continue;
      SetDiagnosis d;
      d.set = s;
      d.contrast = study.contrast(s, sims[0]);
      std::vector<EffectSignature> sig;
      for (std::size_t e = 0; e < effects.size(); ++e)
        sig.push_back({effects[e].name, effects[e].plausible - effects[e].neutral,
                       study.model_contrast(d.contrast, sims[1 + e], sims[0]), effects[e].scale_min(), effects[e].scale_max(),
                       effects[e].identifiable_at(study.rate_count(d.contrast))});
      d.linear = decide_contrast(d.contrast.difference, d.contrast.weight, sig, study.dof(), o->decide);
      d.decision = d.linear;
      d.before = study.curve_contrast(d.contrast, sims[0], sims[0]);
      out.push_back(std::move(d));
    }
    confirm_contrasts(study, effects, sims[0], out, o->confirm, o->confirm_iterations, o->decide, std::cerr);
    if (o->pairs > 0) confirm_contrast_pairs(study, sets, effects, sims, out, o->pairs, o->pair_iterations, o->decide, std::cerr);

    const ContrastReport report{sets,     effects, cal, study, out, simulator.max_kinetic_to_elastic(),
                                simulator.max_probe_kinetic_to_elastic(),
                                finer ? &*finer : nullptr, o->finer, simulator.dynamic_warning(), scaled};
    const std::string md = contrast_markdown(report);
    std::ofstream(o->out / "diagnose.md") << md;
    std::ofstream(o->out / "diagnose.json") << contrast_json(report);
    try {
      plot_contrasts(report, o->out / "contrasts.png");
    } catch (const std::exception& e) {
      fmt::print(stderr, "warning: no plot: {}\n", e.what());
    }
    fmt::print("{}", md);
    ctx.exit_code = 0;
  });
}

}  // namespace shard
