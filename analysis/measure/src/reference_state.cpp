#include "shard/measure/reference_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <variant>

namespace shard::measure {
namespace {

// The component of a vector parameter the effect moves: the place of "{}" among the items of
// its value_format ("[0.0, 0.0, {}]" -> 2); 0 for a scalar.
std::size_t moved_component(const CandidateEffect& effect) {
  const auto at = effect.value_format.find("{}");
  if (at == std::string::npos) return 0;
  return static_cast<std::size_t>(std::count(effect.value_format.begin(), effect.value_format.begin() + at, ','));
}

std::optional<double> override_value(const SceneOverride::Value& v, std::size_t component) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  if (const auto* x = std::get_if<Vec3>(&v); x && component < 3) return (*x)[static_cast<Eigen::Index>(component)];
  if (const auto* a = std::get_if<std::vector<double>>(&v); a && component < a->size()) return (*a)[component];
  return std::nullopt;
}

// Reads "0.5" for a scalar and "gravity z -9.81" for a component, in messages.
std::string state_text(const CandidateEffect& e, double value) {
  return e.value_format.empty() ? fmt::format("{:g}", value)
                                : fmt::format("{:g} (component {} of {})", value, moved_component(e), e.value_format);
}

CandidateEffect centred(CandidateEffect e, double state, std::ostream& log) {
  if (!(e.min <= state && state <= e.max))
    throw std::runtime_error(fmt::format(
        "{}: effect '{}' moves {} over [{:g}, {:g}], but the reference's model has {} there (its scene, a --set, or "
        "a base parameter fitted on the reference): no size of the effect gives back the reference, so its "
        "contrasts would be measured from a model it cannot reach. Fix: widen the effect's min/max to include {:g}, "
        "or give the scene a value of {} inside the range",
        e.origin.empty() ? "effect library" : e.origin, e.name, e.parameter, e.min, e.max, state_text(e, state),
        state, e.parameter));
  if (state == e.neutral) return e;
  const double step = e.plausible - e.neutral;
  const bool fits = e.min <= state + step && state + step <= e.max;
  log << fmt::format("diagnose: {} moves from the reference's {} = {} (library neutral {:g}), trial step {:+g}\n",
                     e.name, e.parameter, state_text(e, state), e.neutral, fits ? step : -step);
  e.neutral = state;
  e.plausible = fits ? state + step : state - step;
  return e;
}

}  // namespace

std::optional<double> effect_state(const ModelPlan& model, const CandidateEffect& effect) {
  if (effect.post_processing()) return model.machine_compliance;
  const std::size_t component = moved_component(effect);
  for (auto it = model.overrides.rbegin(); it != model.overrides.rend(); ++it)
    if (it->key == effect.parameter) return override_value(it->value, component);
  return scene_file_number(model.scene, effect.parameter, component);
}

std::vector<CandidateEffect> centred_on_reference(std::vector<CandidateEffect> effects, const ModelPlan& reference,
                                                  std::ostream& log) {
  for (auto& e : effects) {
    // A machine compliance is added to the model's own (with_effect), so it starts at the reference.
    if (e.post_processing()) continue;
    if (const auto state = effect_state(reference, e)) e = centred(std::move(e), *state, log);
  }
  return effects;
}

void check_effects_reach(const std::vector<CandidateEffect>& effects, const ModelPlan& reference) {
  std::ostream quiet(nullptr);
  centred_on_reference(effects, reference, quiet);
}

}  // namespace shard::measure
