#include "shard/driver/run_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <sstream>

#include "run_loop_parts.hpp"
#include "run_scene.hpp"
#include "serial_backend.hpp"
#include "shard/analysis/quasi_static.hpp"
#include "shard/checkpoint.hpp"
#include "shard/driver/output_folder.hpp"
#include "shard/driver/time_step_report.hpp"
#include "shard/output.hpp"
#include "shard/plugin_host.hpp"
#include "shard/run_file.hpp"
#include "shard/scene.hpp"
#include "shard/version.hpp"

namespace shard::driver {
// The pieces of run_scene.cpp: run_loop_parts.hpp.
namespace detail {

// The run loop's own state that a checkpoint must carry besides the simulation's.
void save_loop_state(Checkpoint& c, const RunResult& r, int frames_written, const std::vector<double>& health) {
  c.numbers = {{"frames_written", frames_written},
               {"peak_load", r.peak_load},
               {"displacement_at_peak", r.displacement_at_peak},
               {"max_kinetic_to_elastic", r.max_kinetic_to_elastic}};
  c.arrays = {{"load", r.curve.force},
              {"displacement", r.curve.displacement},
              {"time_series", r.curve.time},
              {"kinetic_before_break", r.kinetic_before_break},
              {"elastic_before_break", r.elastic_before_break},
              {"health", health}};
}

void restore_loop_state(const Checkpoint& c, RunResult& r, int& frames_written) {
  frames_written = static_cast<int>(c.number("frames_written"));
  r.peak_load = c.number("peak_load");
  r.displacement_at_peak = c.number("displacement_at_peak");
  r.max_kinetic_to_elastic = c.number("max_kinetic_to_elastic");
  r.curve.force = c.array("load");
  r.curve.displacement = c.array("displacement");
  r.curve.time = c.array("time_series");
  r.kinetic_before_break = c.array("kinetic_before_break");
  r.elastic_before_break = c.array("elastic_before_break");
}

// True when a line of the scene reads `breakage = true` (blanks allowed around the words).
// Plain scanning: GCC 12 warns falsely inside std::regex in the sanitizer build.
bool explicitly_sets_breakage(const std::string& scene_text) {
  std::istringstream lines(scene_text);
  for (std::string line; std::getline(lines, line);) {
    std::string compact;
    for (char ch : line)
      if (ch != ' ' && ch != '\t') compact += ch;
    if (compact.rfind("breakage=true", 0) == 0) return true;
  }
  return false;
}

// What a restart may change: when the run ends. Every other key made the state in the checkpoint.
bool restart_may_change(const std::string& key) { return key == "simulation.duration" || key.rfind("stop.", 0) == 0; }

// The run file's scene with the restart's overrides. The frame and series schedule stays the
// run's own (by default it follows the duration), so the rows already written keep their places.
// A --set that repeats the run's own value (the first command line given again) changes nothing.
Scene restart_scene(const RunSpec& spec, const RunMetadata& meta, const PluginHost& host) {
  const Scene old = load_scene_text(meta.scene_text, meta.scene_file, host);
  for (const auto& o : spec.overrides)
    if (!restart_may_change(o.key) &&
        load_scene_text(meta.scene_text, meta.scene_file, host, SceneOverrides{o}).resolved_text != old.resolved_text)
      throw SceneError(fmt::format(
          "--restart {} with --set {}: a restart continues the state in the checkpoint, which the run's own {} made; "
          "only simulation.duration and [stop] keys may change on a restart (run the scene again for the others)",
          spec.restart.string(), o.text(), o.key));
  if (spec.overrides.empty()) return old;
  SceneOverrides o = spec.overrides;
  o.push_back({"output.frame_interval", old.frame_interval});
  o.push_back({"output.series_interval", old.series_interval});
  return load_scene_text(meta.scene_text, meta.scene_file, host, o);
}

RunStart read_run_start(const RunSpec& spec, const PluginHost& host, const RunLog& log,
                        const std::function<Checkpoint(const std::filesystem::path&)>& read) {
  RunStart start;
  start.restarting = !spec.restart.empty();
  if (start.restarting) {
    if (!std::filesystem::is_regular_file(spec.restart))
      throw OutputError(fmt::format("--restart {}: no such run file; give the run.h5 of the run to continue",
                                    spec.restart.string()));
    start.restart_point = read(checkpoint_path_for(spec.restart));
    start.old_meta = RunFile(spec.restart).metadata();
  }
  if (!start.restarting && std::filesystem::is_directory(spec.scene))
    throw SceneError(fmt::format("{}: is a folder, not a scene file; give the .toml file (scenes/ has examples)",
                                 spec.scene.string()));
  start.scene = start.restarting ? restart_scene(spec, start.old_meta, host) : load_scene(spec.scene, host, spec.overrides);
  // Breakage without a bond model is not an error (the default is on, and a contact-only scene
  // is legitimate), but asking for it explicitly means a [bond] section was forgotten.
  if (start.scene.breakage && !start.scene.bond && explicitly_sets_breakage(start.scene.resolved_text) &&
      log.warning)
    log.warning("breakage = true but the scene has no [bond] section: nothing can break. Add [bond] "
                "(plugin = \"beam_bond\") or remove breakage");
  return start;
}

std::string last_good_state(const RunResult& r) {
  return r.checkpoint_step < 0
             ? std::string("No checkpoint was written before it.")
             : fmt::format("The last good state is the checkpoint {} (step {}); after fixing the cause, start "
                           "again from the scene (a restart continues with the same settings)",
                           r.checkpoint.string(), r.checkpoint_step);
}

void prepare_run_output(const RunSpec& spec, const Scene& scene) {
  prepare_output_folder(spec.out_dir, "--out");
  const auto run_file = spec.out_dir / scene.output_file;
  if (std::filesystem::is_directory(run_file))
    throw OutputError(fmt::format("the run file '{}' is a folder; remove it or choose another folder with --out",
                                  run_file.string()));
}

RunMetadataDraft run_metadata(const Scene& scene, const WholeScene& whole, const PluginHost& host) {
  RunMetadataDraft draft;
  RunMetadata& meta = draft.meta;
  const TimeStepReport time_step = time_step_report(scene, whole.limits, whole.dt);
  for (const auto& [key, line] : time_step.limits) {
    draft.lines.push_back(line);
    meta.notes.emplace_back(key, line);
  }
  draft.lines.push_back(time_step.chosen);
  meta.notes.emplace_back("dt", fmt::format("{:.17g}", whole.dt));
  for (const auto& [k, v] : whole.quality) draft.lines.push_back(fmt::format("packing {} = {:.6g}", k, v));
  meta.scene_text = scene.resolved_text;
  meta.scene_file = scene.file.string();
  meta.seed = scene.seed;
  // The code that ran it (shard/version.hpp); git_revision is empty for a build outside git.
  meta.shard_version = std::string(version());
  meta.git_revision = std::string(git_describe());
  meta.generator_quality = whole.quality;
  auto record = [&](PluginKind kind, const char* label, const PluginChoice& c, const std::string& body = {}) {
    const auto& p = host.find(kind, c.name);
    meta.plugins.emplace_back(fmt::format("{}/{}{}", label, c.name, body.empty() ? "" : "/" + body),
                              fmt::format("version={}; file={}; {}", p.info.version, p.file, describe(c.params)));
  };
  // One record per body entry: generator/<plugin>, or generator/<plugin>/<body name> for [[body]].
  for (const auto& b : scene.bodies)
    record(PluginKind::Generator, "generator", b.generator,
           b.from_generator_section ? "" : b.name);
  if (scene.contact) record(PluginKind::Contact, "contact", *scene.contact);
  if (scene.bond) record(PluginKind::Bond, "bond", *scene.bond);
  if (scene.bond)  // the out-of-tree bond effects composed onto the law (docs/how-to/write-a-plugin.md)
    for (const auto* e : host.bond_effects_on(scene.bond->name, scene.bond->params))
      meta.plugins.emplace_back("bond_effect/" + e->info.name,
                                fmt::format("version={}; file={}; on bond/{}", e->info.version, e->file, e->law));
  return draft;
}

// Up to the peak, as shard bending's report counts: after it a softening or brittle fall is the
// failure's own dynamics (reported as transients by compare), not the loading's. Softening bonds
// keep breakage away past the peak: the tiny beam at softening ratio 6.4 (seed 3) read 0.0051
// over all rows before the first break, 0.00028 up to the peak.
double kinetic_to_elastic_up_to_peak(const RunResult& r) {
  const auto& load = r.curve.force;
  const auto peak = static_cast<std::size_t>(std::max_element(load.begin(), load.end()) - load.begin());
  const std::size_t rows = std::min({peak + 1, r.kinetic_before_break.size(), r.elastic_before_break.size()});
  return analysis::max_kinetic_to_elastic(std::span(load).first(std::min(rows, load.size())),
                                          std::span(r.kinetic_before_break).first(rows),
                                          std::span(r.elastic_before_break).first(rows), r.peak_load);
}

}  // namespace detail

RunResult run(const RunSpec& spec, const PluginHost& host, const std::vector<RunObserver*>& observers,
              const RunLog& log) {
  detail::SerialBackend backend;
  return detail::run_scene(spec, host, observers, log, backend);
}

}  // namespace shard::driver
