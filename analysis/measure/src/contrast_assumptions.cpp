// How much each verdict of the contrast diagnosis leans on what the base model assumes
// (docs/explanation/diagnosis.md, "What a verdict rests on").
#include <fmt/format.h>

#include <ostream>

#include "shard/measure/contrast_diagnosis.hpp"

namespace shard::measure {
namespace {

// The effects of the model a set's report shows, at their confirmed values; empty when none.
std::vector<std::pair<const CandidateEffect*, double>> shown_model(const SetDiagnosis& d,
                                                                   const std::vector<CandidateEffect>& effects) {
  if (d.after_effect.empty()) return {};
  if (names_a_pair(d)) {
    const CandidateEffect* a = find_effect(effects, d.pair->first);
    const CandidateEffect* b = find_effect(effects, d.pair->second);
    if (!a || !b) return {};
    return {{a, d.pair_values[0]}, {b, d.pair_values[1]}};
  }
  const CandidateEffect* e = find_effect(effects, d.after_effect);
  if (!e) return {};
  return {{e, d.after_value}};
}

// The multiple of `model` the measured difference asks for: (s' W d) / (s' W s).
double projection(const std::vector<double>& model, const ContrastStudy::Contrast& c) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < model.size(); ++i)
    for (std::size_t j = 0; j < model.size(); ++j) {
      num += model[i] * c.weight[i][j] * c.difference[j];
      den += model[i] * c.weight[i][j] * model[j];
    }
  return den > 0 ? num / den : 0.0;
}

}  // namespace

void check_assumptions_apply(Simulator& simulator, const ModelPlan& base, const SceneOverrides& assumptions) {
  for (const SceneOverride& assumption : assumptions) {
    ModelPlan moved = base;
    moved.overrides.push_back(assumption);
    try {
      simulator.check_model(moved);
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("--assumption {}: {}", assumption.text(), e.what()));
    }
  }
}

void assess_assumptions(ContrastStudy& study, const std::vector<CandidateEffect>& effects,
                        std::vector<SetDiagnosis>& sets, const SceneOverrides& assumptions,
                        const ContrastOptions& decide, std::ostream& log) {
  std::vector<std::size_t> shown;
  for (std::size_t s = 0; s < sets.size(); ++s)
    if (!shown_model(sets[s], effects).empty()) shown.push_back(s);
  if (shown.empty()) return;
  for (const SceneOverride& assumption : assumptions) {
    ModelPlan moved = study.base();
    moved.overrides.push_back(assumption);
    std::vector<ModelPlan> models{moved};
    for (std::size_t s : shown) models.push_back(with_effects(moved, shown_model(sets[s], effects)));
    log << fmt::format("diagnose: base assumption {}: the base and {} shown models again\n", assumption.text(),
                       shown.size());
    const auto runs = study.simulate(models, log);
    for (std::size_t k = 0; k < shown.size(); ++k) {
      SetDiagnosis& d = sets[shown[k]];
      const ContrastStudy::Contrast contrast = study.contrast(d.set, runs[0]);
      const double here = projection(d.after_components, d.contrast);
      AssumptionSensitivity a;
      a.assumption = assumption.text();
      a.size_ratio = here != 0 ? projection(study.model_contrast(contrast, runs[1 + k], runs[0]), contrast) / here : 0;
      a.after = study.curve_contrast(contrast, runs[1 + k], runs[0]);
      a.curve_agrees = curve_agrees(a.after, decide);
      d.assumptions.push_back(std::move(a));
    }
  }
}

}  // namespace shard::measure
