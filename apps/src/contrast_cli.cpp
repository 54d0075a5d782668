// The options and the effect library the contrast commands (diagnose SETS, calibrate SETS) share.
#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>

#include "contrast_report.hpp"

namespace shard {

namespace fs = std::filesystem;
using namespace measure;

void add_contrast_options(CLI::App* cmd, ContrastOptionsCli& o) {
  cmd->add_option("sets", o.sets, "measurement folders (the reference among them)")->required();
  add_simulation_options(cmd, o.model, o.sim);
  cmd->get_option("--scene")->required();
  cmd->add_option("--reference", o.reference,
                  "the set the others are held against (folder or its name); default: the consensus of the others");
  cmd->add_option("--param", o.diagnosis.params,
                  "base parameter section.key fitted to the reference first (its value is read from the scene)");
  cmd->add_option("--base-iterations", o.diagnosis.base_iterations, "Gauss-Newton iterations of the base fit")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--effects", o.library, "candidate-effect library (default: effects.toml next to the scene)");
  cmd->add_option("--only", o.only, "try only these effects of the library (comma-separated)")->delimiter(',');
  cmd->add_option("--form-tolerance", o.diagnosis.decide.form_tolerance,
                  "share of an effect's simulated contrast by which the lab's may differ in form (0: exact shape)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--own-scatter", o.diagnosis.decide.own_scatter_p,
                  "a set whose specimens scatter beyond the others' at this p (e.g. 0.01) carries its own scatter "
                  "instead of joining the pooled one (default 0: every set pooled)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--lab-grain-size", o.diagnosis.lab_grain_size,
               "run the model at the reference's reported grain size ([test] grain_size in metadata.toml): the "
               "scene's diameters scaled to it (cost ~ (scene mean / grain)^4 per run)");
  cmd->add_option("--confirm-iterations", o.diagnosis.confirm_iterations,
                  "confirmation passes: the first at the linear size, later ones at the size the runs ask for")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--confirm-probes", o.diagnosis.confirm_probes,
                  "rounds of runs a factor sqrt(2) either side of a closest effect's size that leaves a remainder "
                  "beyond noise (0: none)")
      ->check(CLI::NonNegativeNumber);
}

std::vector<CandidateEffect> contrast_effects(const ContrastOptionsCli& o) {
  const fs::path library = o.library.empty() ? o.model.scene.parent_path() / "effects.toml" : o.library;
  if (!fs::exists(library))
    throw std::runtime_error(fmt::format("{}: the effect library (candidate effects to try) does not exist. Fix: pass "
                                         "--effects FILE, e.g. --effects scenes/measurements/effects.toml",
                                         library.string()));
  return select_effects(read_effect_library(library), o.only);
}

}  // namespace shard
