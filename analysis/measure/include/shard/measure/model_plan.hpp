#pragma once
// A model of a test: a scene, the overrides that make it this model version, and what is applied
// to its curves afterwards (the testing machine's compliance), at a loading rate. The diagnoses
// build every model they try from a base plan with these functions, so an effect is applied to a
// model in one place.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shard/measure/effect_library.hpp"
#include "shard/scene_override.hpp"

namespace shard::measure {

struct ModelPlan {
  std::filesystem::path scene;
  SceneOverrides overrides;       // typed; --set strings are parsed at the command line
  double machine_compliance = 0;  // m/N, series spring applied to the simulated curves
  double loading_rate = 0;        // m/s of the loading pins; 0 = the scene's own
  // An effect's trial at its library size (a probe for its signature, not a model of the data):
  // its kinetic/elastic ratio is kept apart from the dynamic warning (a lubricated-roller trial
  // whose beam slides is dynamic, the model of the data need not be).
  bool probe = false;
};

// Above this kinetic/elastic energy ratio before breakage (with the load >= 20 % of its peak) a
// run is called dynamic. The resolved bending scene stays at or below 1.2e-4 with F_max moving
// < 1 % at half its rate; the damped tiny beam sits at 0.008-0.03 at 0.02 m/s, where its curve
// still moves < 2 % over a 4x rate change, so above the bound the warning asks for that check
// (shard bending-rate-check) rather than proving inertia.
inline constexpr double kDynamicKineticToElastic = 1e-2;

ModelPlan with_effect(ModelPlan model, const CandidateEffect& effect, double value);
// Several effects on at once, each (effect, value) in turn.
ModelPlan with_effects(ModelPlan model, const std::vector<std::pair<const CandidateEffect*, double>>& effects);
ModelPlan with_parameters(ModelPlan model, const std::vector<std::string>& keys, const std::vector<double>& values);

// The number the scene file gives `key`, without overrides: "section.key" (for an array value its
// `component`), or "material_pair.A.B.key" from the row of materials A and B (either order), else
// from the default row ["*", "*"], as the scene loader fills a pair (docs/reference/materials.md).
// None when the file gives none.
std::optional<double> scene_file_number(const std::filesystem::path& scene, const std::string& key,
                                        std::size_t component = 0);

// The value of section.key in the resolved scene file (overrides applied); throws when absent.
double scene_number(const ModelPlan& model, const std::string& key);

}  // namespace shard::measure
