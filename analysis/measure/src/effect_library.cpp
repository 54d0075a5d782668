#include "shard/measure/effect_library.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <toml++/toml.h>

namespace shard::measure {
namespace {

std::string where(const std::filesystem::path& file, const toml::node& n) {
  return fmt::format("{}:{}:{}", file.string(), n.source().begin.line, n.source().begin.column);
}

}  // namespace

std::string CandidateEffect::scene_value(double value) const {
  const std::string number = fmt::format("{:.12g}", value);
  if (value_format.empty()) return number;
  std::string out = value_format;
  out.replace(out.find("{}"), 2, number);
  return out;
}

double CandidateEffect::scale_min() const {
  const double step = plausible - neutral;
  return step > 0 ? (min - neutral) / step : (max - neutral) / step;
}

double CandidateEffect::scale_max() const {
  const double step = plausible - neutral;
  return step > 0 ? (max - neutral) / step : (min - neutral) / step;
}

double CandidateEffect::value_at(double scale) const {
  return std::clamp(neutral + scale * (plausible - neutral), min, max);
}

std::vector<std::string> CandidateEffect::overrides(double value) const {
  std::vector<std::string> out = set;
  if (!post_processing()) out.push_back(parameter + "=" + scene_value(value));
  return out;
}

std::vector<CandidateEffect> read_effect_library(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file))
    throw std::runtime_error(fmt::format(
        "{}: the candidate-effect library (the effects `shard diagnose` and `shard calibrate-effect` try) does not "
        "exist. Fix: pass --effects FILE, or copy scenes/measurements/effects.toml beside the scene (the default is "
        "effects.toml in the scene's folder)",
        std::filesystem::absolute(file).lexically_normal().string()));
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw std::runtime_error(fmt::format("{}:{}:{}: {}", file.string(), e.source().begin.line, e.source().begin.column,
                                         e.description()));
  }
  const auto* effects = root["effect"].as_array();
  if (!effects || effects->empty())
    throw std::runtime_error(fmt::format("{}: no [[effect]] tables; see docs/measurements.md for the format", file.string()));
  std::vector<CandidateEffect> out;
  for (const auto& node : *effects) {
    const auto* t = node.as_table();
    if (!t) throw std::runtime_error(fmt::format("{}: [[effect]] must be a table", where(file, node)));
    CandidateEffect e;
    for (const auto& [key, value] : *t) {
      const std::string k(key.str());
      if (k == "name" || k == "parameter" || k == "unit" || k == "separated_by" || k == "doc") {
        const auto* s = value.as_string();
        if (!s) throw std::runtime_error(fmt::format("{}: '{}' must be a string", where(file, value), k));
        (k == "name" ? e.name : k == "parameter" ? e.parameter : k == "unit" ? e.unit : k == "doc" ? e.doc : e.separated_by) = s->get();
      } else if (k == "value_format") {
        const auto* s = value.as_string();
        const std::string text = s ? s->get() : "";
        const auto at = text.find("{}");
        if (!s || at == std::string::npos || text.find("{}", at + 2) != std::string::npos)
          throw std::runtime_error(fmt::format(
              "{}: 'value_format' must be a string with one {{}} where the value goes, e.g. \"[0.0, 0.0, {{}}]\"",
              where(file, value)));
        e.value_format = text;
      } else if (k == "neutral" || k == "plausible" || k == "min" || k == "max") {
        const auto v = value.value<double>();
        if (!v) throw std::runtime_error(fmt::format("{}: '{}' must be a number", where(file, value), k));
        (k == "neutral" ? e.neutral : k == "plausible" ? e.plausible : k == "min" ? e.min : e.max) = *v;
      } else if (k == "set") {
        const auto* a = value.as_array();
        if (!a) throw std::runtime_error(fmt::format("{}: 'set' must be an array of \"section.key=value\" strings", where(file, value)));
        for (const auto& item : *a) {
          const auto s = item.value<std::string>();
          if (!s || s->find('=') == std::string::npos)
            throw std::runtime_error(fmt::format("{}: each 'set' entry is a \"section.key=value\" string", where(file, item)));
          e.set.push_back(*s);
        }
      } else {
        throw std::runtime_error(fmt::format(
            "{}: unknown key '{}' in [[effect]]; the keys are name, parameter, value_format, unit, neutral, "
            "plausible, min, max, set, separated_by, doc",
            where(file, value), k));
      }
    }
    if (e.name.empty() || e.parameter.empty())
      throw std::runtime_error(fmt::format("{}: an [[effect]] needs a name and a parameter", where(file, node)));
    if (!(e.min <= e.neutral && e.neutral <= e.max && e.min <= e.plausible && e.plausible <= e.max))
      throw std::runtime_error(fmt::format("{}: effect '{}': neutral {:g} and plausible {:g} must lie in [min, max] = [{:g}, {:g}]",
                                           where(file, node), e.name, e.neutral, e.plausible, e.min, e.max));
    if (e.plausible == e.neutral)
      throw std::runtime_error(fmt::format("{}: effect '{}': plausible equals neutral, the trial run would not switch "
                                           "it on",
                                           where(file, node), e.name));
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<CandidateEffect> select_effects(const std::vector<CandidateEffect>& library,
                                            const std::vector<std::string>& names) {
  if (names.empty()) return library;
  std::vector<CandidateEffect> out;
  for (const auto& n : names) {
    bool found = false;
    for (const auto& e : library)
      if (e.name == n) out.push_back(e), found = true;
    if (!found) {
      std::string valid;
      for (const auto& e : library) valid += (valid.empty() ? "" : ", ") + e.name;
      throw std::runtime_error(fmt::format("unknown effect '{}'; the library has: {}", n, valid));
    }
  }
  return out;
}

}  // namespace shard::measure
