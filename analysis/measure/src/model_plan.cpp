#include "shard/measure/model_plan.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <array>
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

namespace {

std::optional<double> number_of(const toml::node_view<const toml::node>& node, std::size_t component) {
  if (const auto* a = node.as_array()) return component < a->size() ? (*a)[component].value<double>() : std::nullopt;
  return node.value<double>();
}

bool row_of(const toml::table& row, const std::string& a, const std::string& b) {
  const auto* names = row["materials"].as_array();
  if (names == nullptr || names->size() != 2) return false;
  const std::array<std::string, 2> given{(*names)[0].value_or(std::string()), (*names)[1].value_or(std::string())};
  return (given[0] == a && given[1] == b) || (given[0] == b && given[1] == a);
}

// A pair's own row gives the key, else the default row: key by key, as the scene loader fills it.
std::optional<double> material_pair_number(const toml::table& root, const std::string& a, const std::string& b,
                                           const std::string& key) {
  const auto* rows = root["material_pair"].as_array();
  if (rows == nullptr) return std::nullopt;
  std::optional<double> fallback;
  for (const auto& node : *rows) {
    const auto* row = node.as_table();
    if (row == nullptr || !row->contains(key)) continue;
    if (row_of(*row, a, b)) return (*row)[key].value<double>();
    if (row_of(*row, "*", "*")) fallback = (*row)[key].value<double>();
  }
  return fallback;
}

}  // namespace

std::optional<double> scene_file_number(const std::filesystem::path& scene, const std::string& key,
                                        std::size_t component) {
  if (scene.empty() || !std::filesystem::exists(scene)) return std::nullopt;
  const toml::table root = toml::parse_file(scene.string());
  const auto parts = scene_key_parts(key);
  if (parts.size() == 4 && parts[0] == "material_pair") return material_pair_number(root, parts[1], parts[2], parts[3]);
  if (parts.size() != 2) return std::nullopt;
  return number_of(root[parts[0]][parts[1]], component);
}

double scene_number(const ModelPlan& model, const std::string& key) {
  // The last override of the key wins, as in the scene loader; otherwise the scene file's value.
  for (auto it = model.overrides.rbegin(); it != model.overrides.rend(); ++it)
    if (it->key == key) {
      if (const auto* d = std::get_if<double>(&it->value)) return *d;
      if (const auto* i = std::get_if<std::int64_t>(&it->value)) return static_cast<double>(*i);
      throw std::runtime_error(fmt::format("--set {}: a number is needed here", it->text()));
    }
  const auto v = scene_file_number(model.scene, key);
  if (!v)
    throw std::runtime_error(fmt::format("{}: no number {} in the scene: set it there or with --set {}=value",
                                         model.scene.string(), key, key));
  return *v;
}

}  // namespace shard::measure
