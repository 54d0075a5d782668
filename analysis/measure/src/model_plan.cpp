#include "shard/measure/model_plan.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cstdint>
#include <stdexcept>
#include <variant>

#include "shard/measure/significant_digits.hpp"

namespace shard::measure {

ModelPlan with_effect(ModelPlan model, const CandidateEffect& effect, double value) {
  if (effect.post_processing()) {
    model.machine_compliance += value;
  } else {
    // The effect library states its values as scene text (value_format): parsed as --set is.
    for (const auto& s : effect.overrides(value)) model.overrides.push_back(SceneOverride::parse(s));
  }
  return model;
}

ModelPlan with_effects(ModelPlan model, const std::vector<std::pair<const CandidateEffect*, double>>& effects) {
  for (const auto& [effect, value] : effects) model = with_effect(std::move(model), *effect, value);
  return model;
}

ModelPlan with_parameters(ModelPlan model, const std::vector<std::string>& keys, const std::vector<double>& values) {
  for (std::size_t i = 0; i < keys.size(); ++i) model.overrides.push_back({keys[i], significant(values[i], 12)});
  return model;
}

double scene_number(const ModelPlan& model, const std::string& key) {
  // The last override of the key wins, as in the scene loader; otherwise the scene file's value.
  for (auto it = model.overrides.rbegin(); it != model.overrides.rend(); ++it)
    if (it->key == key) {
      if (const auto* d = std::get_if<double>(&it->value)) return *d;
      if (const auto* i = std::get_if<std::int64_t>(&it->value)) return static_cast<double>(*i);
      throw std::runtime_error(fmt::format("--set {}: a number is needed here", it->text()));
    }
  const toml::table root = toml::parse_file(model.scene.string());
  const auto dot = key.find('.');
  const auto v = root[key.substr(0, dot)][key.substr(dot + 1)].value<double>();
  if (!v)
    throw std::runtime_error(fmt::format("{}: no number {} in the scene: set it there or with --set {}=value",
                                         model.scene.string(), key, key));
  return *v;
}

}  // namespace shard::measure
