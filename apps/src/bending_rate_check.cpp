// `shard bending-rate-check scene.toml`: the four-point bending scene at its loading rate and at
// a fraction of it (default half), same packing, and the change of F_max and of the initial
// stiffness against the < 3 % / < 2 % criteria (docs/explanation/four-point-bending.md: "result unchanged when the
// rate is halved").
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>

#include "bending_commands.hpp"
#include "option_checks.hpp"
#include "shard/driver/output_folder.hpp"
#include "shard/app/commands.hpp"
#include "shard/app/run_command.hpp"
#include "shard/bending/bending_run.hpp"
#include "shard/bending/rate_check.hpp"
#include "shard/io/json.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"
#include "shard/measure/significant_digits.hpp"

namespace shard {
namespace {

struct RateCheckCliOptions {
  std::filesystem::path scene;
  std::vector<std::string> overrides;
  std::filesystem::path out_dir = "rate_check";
  double factor = 0.5;
  int threads = 0;
  bending::RateCheckCriteria criteria;
};

// The overrides that slow the loading walls by `factor` and stretch the duration to match (the
// stop rule still ends the run at failure).
SceneOverrides slowed_overrides(const RateCheckCliOptions& o, const Scene& scene) {
  SceneOverrides out = parse_overrides(o.overrides);
  if (scene.stop.load_walls.empty())
    throw std::runtime_error(fmt::format("{}: [stop] load_walls is empty: the rate check needs the loading walls named "
                                         "there (e.g. load_walls = [\"pin_left\", \"pin_right\"])",
                                         o.scene.string()));
  for (const auto& name : scene.stop.load_walls) {
    const auto it = std::find_if(scene.walls.begin(), scene.walls.end(), [&](const Wall& w) { return w.name == name; });
    if (it == scene.walls.end())
      throw std::runtime_error(fmt::format("{}: [stop] load_walls names '{}', which is no [[wall]]", o.scene.string(), name));
    if (it->velocity.norm() == 0)
      throw std::runtime_error(fmt::format("{}: loading wall '{}' does not move (velocity zero)", o.scene.string(), name));
    out.push_back({fmt::format("wall.{}.velocity", name), significant(Vec3(o.factor * it->velocity), 9)});
    if (it->motion.ramp != WallRamp::None)  // the same ramp travel at the slower speed
      out.push_back({fmt::format("wall.{}.ramp_time", name), significant(it->motion.ramp_time / o.factor, 9)});
  }
  out.push_back({"simulation.duration", significant(scene.duration / o.factor, 9)});
  return out;
}

// rate_check.json: each measured figure as [at the scene's rate, at the reduced rate].
constexpr int kRateCheckFormat = 1;
io::Json rate_check_json(const RateCheckCliOptions& o, const bending::BendingReport& fast,
                         const bending::BendingReport& slow, const bending::RateCheck& check) {
  io::Json j = io::json_document(kRateCheckFormat);
  j["scene"] = o.scene.string();
  j["factor"] = o.factor;
  j["speed_m_per_s"] = {fast.quasi_static.loading_speed, slow.quasi_static.loading_speed};
  j["force_max_N"] = {fast.analysis.force_max, slow.analysis.force_max};
  j["stiffness_N_per_m"] = {fast.analysis.stiffness, slow.analysis.stiffness};
  j["youngs_modulus_Pa"] = {fast.analysis.youngs_modulus, slow.analysis.youngs_modulus};
  j["deflection_at_peak_m"] = {fast.analysis.deflection_at_peak, slow.analysis.deflection_at_peak};
  j["force_max_change"] = check.force_max_change;
  j["stiffness_change"] = check.stiffness_change;
  j["passed"] = check.passed();
  return j;
}

int rate_check_command(const RateCheckCliOptions& o, const CommandContext& ctx) {
  if (!(o.factor > 0 && o.factor < 1))
    throw std::runtime_error(fmt::format("--factor {}: the reduced rate is a fraction of the scene's, 0 < factor < 1", o.factor));
  PluginHost host;
  load_plugins(host, ctx.plugin_dirs, std::cerr);
  const Scene scene = load_scene(o.scene, o.overrides, host);
  prepare_output_folder(o.out_dir, "--out");
  std::ofstream log(o.out_dir / "rate_check.log");

  auto run = [&](const SceneOverrides& overrides, const std::string& name) {
    RunOptions r;
    r.scene = o.scene;
    r.overrides = overrides;
    r.out_dir = o.out_dir / name;
    r.plugin_dirs = ctx.plugin_dirs;
    r.threads = o.threads;
    r.quiet = true;
    const RunSummary s = run_scene(r, log);
    auto report = bending::analyse_bending_run(s.output);
    fmt::print("  {} run: {} ({} steps, {:.0f} s wall): F_max = {:.5g} N, k = {:.5g} N/mm\n", name, s.output.string(),
               s.steps, s.wall_seconds, report.analysis.force_max, 1e-3 * report.analysis.stiffness);
    std::fflush(stdout);
    return report;
  };
  fmt::print("rate check of {} (factor {:g}); runs in {}\n", o.scene.string(), o.factor, o.out_dir.string());
  const auto fast = run(parse_overrides(o.overrides), "rate");
  const auto slow = run(slowed_overrides(o, scene), "slow");
  const auto check = bending::compare_rates(fast.analysis, slow.analysis, o.criteria);
  fmt::print("{}", bending::format_rate_check(fast.analysis, slow.analysis, fast.quasi_static.loading_speed,
                                              slow.quasi_static.loading_speed, check, o.criteria));
  fmt::print("  kinetic/elastic before damage: {:.3g} (rate), {:.3g} (slow); crack at {:+.1f} / {:+.1f} mm\n",
             fast.quasi_static.max_kinetic_to_elastic, slow.quasi_static.max_kinetic_to_elastic,
             1e3 * fast.crack.position, 1e3 * slow.crack.position);
  io::write_json(o.out_dir / "rate_check.json", rate_check_json(o, fast, slow, check));
  return check.passed() ? 0 : 2;
}

}  // namespace

void add_bending_rate_check_command(CLI::App& app, CommandContext& ctx) {
  auto o = std::make_shared<RateCheckCliOptions>();
  auto* c = app.add_subcommand("bending-rate-check", "run a four-point bending scene at its loading rate and at half of "
                                                     "it (same packing); pass when F_max changes < 3 % and the "
                                                     "stiffness < 2 %");
  c->add_option("scene", o->scene, "four-point bending scene .toml")->required()->check(CLI::ExistingFile);
  c->add_option("--set", o->overrides, "scene overrides applied to both runs");
  c->add_option("--out", o->out_dir, "output folder (default ./rate_check)");
  c->add_option("--factor", o->factor, "reduced rate as a fraction of the scene's (default 0.5)");
  c->add_option("--max-force-change", o->criteria.force_max, "criterion on |F_max change| (default 0.03)");
  c->add_option("--max-stiffness-change", o->criteria.stiffness, "criterion on |stiffness change| (default 0.02)");
  c->add_option("--threads", o->threads, "OpenMP threads per run")->check(thread_count());
  c->callback([o, &ctx] { ctx.exit_code = rate_check_command(*o, ctx); });
}

}  // namespace shard
