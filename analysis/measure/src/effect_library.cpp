#include "shard/measure/effect_library.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <toml++/toml.h>
#include <variant>

#include "shard/measure/features.hpp"
#include "shard/measure/statistics.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene_override.hpp"

namespace shard::measure {
namespace {

std::string where(const std::filesystem::path& file, const toml::node& n) {
  return fmt::format("{}:{}:{}", file.string(), n.source().begin.line, n.source().begin.column);
}

}  // namespace

SchemaNeutral plugin_schema_neutrals() {
  // Loaded on the first plugin parameter asked for, once per library read.
  auto host = std::make_shared<std::unique_ptr<PluginHost>>();
  return [host](const std::string& parameter) -> std::optional<double> {
    const auto dot = parameter.find('.');
    const std::string section = parameter.substr(0, dot);
    if (dot == std::string::npos || (section != "bond" && section != "contact")) return std::nullopt;
    if (!*host) {
      *host = std::make_unique<PluginHost>();
      (*host)->load_directories(PluginHost::default_search_path());
    }
    const PluginKind kind = section == "bond" ? PluginKind::Bond : PluginKind::Contact;
    const std::string key = parameter.substr(dot + 1);
    std::optional<double> neutral;
    std::string declared_by;
    for (const LoadedPlugin* plugin : (*host)->plugins()) {
      if (plugin->info.kind != kind) continue;
      for (const auto& spec : plugin->info.params) {
        if (spec.name != key || !spec.neutral) continue;
        if (neutral && *neutral != *spec.neutral)
          throw std::runtime_error(fmt::format("{} plugins declare different neutral values for {} ({:g} in {}, {:g} in {})",
                                               section, key, *neutral, declared_by, *spec.neutral, plugin->info.name));
        neutral = spec.neutral;
        declared_by = plugin->info.name;
      }
    }
    return neutral;
  };
}

ParameterRange plugin_parameter_range(const std::string& parameter, const std::vector<std::filesystem::path>& extra_dirs) {
  ParameterRange range;
  const auto dot = parameter.find('.');
  const std::string section = parameter.substr(0, dot);
  if (dot == std::string::npos || (section != "bond" && section != "contact")) return range;
  PluginHost host;
  host.load_directories(PluginHost::default_search_path(extra_dirs));
  const PluginKind kind = section == "bond" ? PluginKind::Bond : PluginKind::Contact;
  const std::string key = parameter.substr(dot + 1);
  for (const LoadedPlugin* plugin : host.plugins()) {
    if (plugin->info.kind != kind) continue;
    for (const auto& spec : plugin->info.params)
      if (spec.name == key) {
        range.min = std::max(range.min, spec.min);
        range.max = std::min(range.max, spec.max);
      }
  }
  return range;
}

const CandidateEffect* find_effect(const std::vector<CandidateEffect>& effects, const std::string& name) {
  for (const auto& e : effects)
    if (e.name == name) return &e;
  return nullptr;
}

std::string CandidateEffect::scene_value(double value) const {
  const std::string number = fmt::format("{:.12g}", value);
  if (value_format.empty()) return number;
  std::string out = value_format;
  out.replace(out.find("{}"), 2, number);
  return out;
}

std::string CandidateEffect::plugin_set_for(const std::string& section) const {
  for (const SceneOverride& o : parse_overrides(set))
    if (o.key == section + ".plugin")
      if (const auto* plugin = std::get_if<std::string>(&o.value)) return *plugin;
  return "";
}

namespace {

std::string section_of(const std::string& parameter) {
  const auto dot = parameter.find('.');
  return dot == std::string::npos ? "" : parameter.substr(0, dot);
}

// b's parameter lives under the plugin the scene (or b's own `set`) gives its section: a plugin
// that `a` switches that section to does not take it.
bool switches_away_from(const CandidateEffect& a, const CandidateEffect& b) {
  const std::string section = section_of(b.parameter);
  if (section.empty()) return false;
  const std::string plugin = a.plugin_set_for(section);
  return !plugin.empty() && plugin != b.plugin_set_for(section);
}

}  // namespace

bool combinable(const CandidateEffect& a, const CandidateEffect& b) {
  return !switches_away_from(a, b) && !switches_away_from(b, a);
}

std::string CandidateEffect::unit_suffix() const { return unit.empty() || unit == "1" ? "" : " " + unit; }

std::string CandidateEffect::sized(double value) const { return fmt::format("{:.4g}{}", value, unit_suffix()); }

// A rate effect that stayed within the scatter over the rates the data have is told by a wider
// span of rates (it grows with the logarithm of the rate) or by a narrower scatter.
std::string CandidateEffect::separating_measurement(const DataCoverage& data) const {
  if (rates_needed > 1 && identifiable_at(data))
    return fmt::format("loading rates farther apart than these {} (a rate effect grows with the logarithm of the "
                       "rate: a decade or more between the slowest and the fastest), or more specimens per rate",
                       data.rates);
  return separated_by;
}

std::string CandidateEffect::needs_beyond(const DataCoverage& data) const {
  if (lacks_rates(data)) return fmt::format("{} loading rates", rates_needed);
  if (lacks_sizes(data)) return fmt::format("{} specimen sizes", sizes_needed);
  return "";
}

std::string CandidateEffect::unidentifiable_reason(const DataCoverage& data) const {
  const auto plural = [](std::size_t n) { return n == 1 ? "" : "s"; };
  if (lacks_rates(data))
    return fmt::format("a rate effect at {} loading rate{} changes only the curve's shape, which rate-independent "
                       "effects change too: it is named only with {}",
                       data.rates, plural(data.rates), needs_beyond(data));
  if (lacks_sizes(data))
    return fmt::format("at {} specimen size{} it changes the curves as other causes do; its own mark is how it "
                       "scales with the specimen's size (a strength scatter: the larger specimen the weaker, the "
                       "Weibull size effect), so it is named only with {}",
                       data.sizes, plural(data.sizes), needs_beyond(data));
  return "";
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

namespace {

// One key of an [[effect]] table into `e`; `has_neutral` is set when it is the neutral value.
void read_effect_key(const std::filesystem::path& file, const std::string& k, const toml::node& value,
                     CandidateEffect& e, bool& has_neutral) {
  if (k == "name" || k == "parameter" || k == "unit" || k == "separated_by" || k == "doc" || k == "plausible_from") {
    const auto* s = value.as_string();
    if (!s) throw std::runtime_error(fmt::format("{}: '{}' must be a string", where(file, value), k));
    (k == "name"        ? e.name
     : k == "parameter" ? e.parameter
     : k == "unit"      ? e.unit
     : k == "doc"       ? e.doc
     : k == "plausible_from" ? e.plausible_from
                             : e.separated_by) = s->get();
    if (k == "plausible_from") try {
        TestScales{}.at(e.plausible_from);
      } catch (const std::exception&) {
        throw std::runtime_error(fmt::format("{}: unknown plausible_from '{}'; the scales are {}", where(file, value),
                                             e.plausible_from, kTestScaleNames));
      }
  } else if (k == "value_format") {
    const auto* s = value.as_string();
    const std::string text = s ? s->get() : "";
    const auto at = text.find("{}");
    if (!s || at == std::string::npos || text.find("{}", at + 2) != std::string::npos)
      throw std::runtime_error(fmt::format(
          "{}: 'value_format' must be a string with one {{}} where the value goes, e.g. \"[0.0, 0.0, {{}}]\"",
          where(file, value)));
    e.value_format = text;
  } else if (k == "neutral" || k == "plausible" || k == "min" || k == "max" || k == "plausible_factor") {
    const auto v = value.value<double>();
    if (!v) throw std::runtime_error(fmt::format("{}: '{}' must be a number", where(file, value), k));
    has_neutral = has_neutral || k == "neutral";
    (k == "neutral"     ? e.neutral
     : k == "plausible" ? e.plausible
     : k == "min"       ? e.min
     : k == "max"       ? e.max
                        : e.plausible_factor) = *v;
  } else if (k == "rates_needed" || k == "sizes_needed") {
    const auto v = value.value<std::int64_t>();
    const bool rates = k == "rates_needed";
    if (!value.is_integer() || !v || *v < 1)
      throw std::runtime_error(fmt::format(
          "{}: '{}' must be a whole number >= 1 (the {} the data need before the effect can be named; 2 for {})",
          where(file, value), k, rates ? "loading rates" : "specimen sizes",
          rates ? "a rate effect such as a viscosity" : "an effect known by its size effect such as a Weibull scatter"));
    (rates ? e.rates_needed : e.sizes_needed) = static_cast<int>(*v);
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
        "plausible, plausible_from, plausible_factor, min, max, rates_needed, sizes_needed, set, separated_by, doc",
        where(file, value), k));
  }
}

// The neutral value is declared once, in the schema of the plugin that carries the parameter.
// Plugins that disagree leave the choice to the entry's own `neutral`.
void resolve_neutral(const std::filesystem::path& file, const toml::node& node, const toml::table& t,
                     CandidateEffect& e, bool has_neutral, const SchemaNeutral& schema) {
  std::optional<double> declared;
  try {
    declared = schema ? schema(e.parameter) : std::nullopt;
  } catch (const std::exception& x) {
    if (!has_neutral)
      throw std::runtime_error(fmt::format("{}: effect '{}': {}; give its neutral = ... here", where(file, node),
                                           e.name, x.what()));
  }
  if (declared && has_neutral && *declared != e.neutral)
    throw std::runtime_error(fmt::format(
        "{}: effect '{}': neutral {:g} contradicts the neutral value {:g} that the plugin's schema declares for {}; "
        "remove the key (the schema's value is used)",
        where(file, *t.get("neutral")), e.name, e.neutral, *declared, e.parameter));
  if (declared) e.neutral = *declared;
  if (!declared && !has_neutral)
    throw std::runtime_error(fmt::format(
        "{}: effect '{}' needs a neutral value (the effect is off): {} is no plugin parameter with a neutral value "
        "in its schema, so give neutral = ... here",
        where(file, node), e.name, e.parameter));
}

// The entry's values against each other: a rule with its factor, neutral and plausible in range.
void check_effect_values(const std::filesystem::path& file, const toml::node& node, CandidateEffect& e) {
  if (e.plausible_from.empty() != (e.plausible_factor == 0))
    throw std::runtime_error(fmt::format("{}: effect '{}': plausible_from and plausible_factor go together (plausible = "
                                         "factor x the scale), e.g. plausible_from = \"time_to_peak\" and "
                                         "plausible_factor = 0.1",
                                         where(file, node), e.name));
  // With a rule, plausible is set once the measurements are known (with_test_plausible).
  const bool rule = !e.plausible_from.empty();
  if (rule) e.plausible = std::numeric_limits<double>::quiet_NaN();
  if (!(e.min <= e.neutral && e.neutral <= e.max && (rule || (e.min <= e.plausible && e.plausible <= e.max))))
    throw std::runtime_error(fmt::format("{}: effect '{}': neutral {:g} and plausible {:g} must lie in [min, max] = [{:g}, {:g}]",
                                         where(file, node), e.name, e.neutral, e.plausible, e.min, e.max));
  if (!rule && e.plausible == e.neutral)
    throw std::runtime_error(fmt::format("{}: effect '{}': plausible equals neutral, the trial run would not switch "
                                         "it on",
                                         where(file, node), e.name));
}

}  // namespace

std::vector<CandidateEffect> read_effect_library(const std::filesystem::path& file, const SchemaNeutral& schema) {
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
    throw std::runtime_error(fmt::format("{}: no [[effect]] tables; see docs/reference/effects.md for the format", file.string()));
  std::vector<CandidateEffect> out;
  for (const auto& node : *effects) {
    const auto* t = node.as_table();
    if (!t) throw std::runtime_error(fmt::format("{}: [[effect]] must be a table", where(file, node)));
    CandidateEffect e;
    e.origin = where(file, node);
    bool has_neutral = false;
    for (const auto& [key, value] : *t) read_effect_key(file, std::string(key.str()), value, e, has_neutral);
    if (e.name.empty() || e.parameter.empty())
      throw std::runtime_error(fmt::format("{}: an [[effect]] needs a name and a parameter", where(file, node)));
    resolve_neutral(file, node, *t, e, has_neutral, schema);
    check_effect_values(file, node, e);
    // Effects are chosen by name (--with, --only) and ranked by name: one name, one effect.
    for (const auto& earlier : out)
      if (earlier.name == e.name)
        throw std::runtime_error(fmt::format("{}: effect name '{}' is used twice in the library; give each [[effect]] "
                                             "its own name",
                                             where(file, *t->get("name")), e.name));
    out.push_back(std::move(e));
  }
  return out;
}

double TestScales::at(const std::string& name) const {
  if (name == "time_to_peak") return time_to_peak;
  if (name == "peak_force") return peak_force;
  if (name == "peak_displacement") return peak_displacement;
  if (name == "secant_compliance") return secant_compliance;
  throw std::invalid_argument(fmt::format("unknown test scale '{}'; the scales are {}", name, kTestScaleNames));
}

TestScales test_scales(const std::vector<std::vector<Specimen>>& rate_groups, double time_compression) {
  TestScales s;
  std::vector<double> f, w;
  s.time_to_peak = std::numeric_limits<double>::infinity();
  for (const auto& group : rate_groups) {
    std::vector<double> t;
    for (const auto& sp : group) {
      const std::size_t p = peak_index(sp.curve);
      t.push_back(sp.curve.time[p] - sp.curve.time.front());
      f.push_back(sp.curve.force[p]);
      w.push_back(sp.curve.displacement[p]);
    }
    if (!t.empty()) s.time_to_peak = std::min(s.time_to_peak, mean(t) / time_compression);
  }
  if (f.empty()) throw std::invalid_argument("test_scales: no specimens");
  s.peak_force = mean(f);
  s.peak_displacement = mean(w);
  s.secant_compliance = s.peak_displacement / s.peak_force;
  return s;
}

std::vector<CandidateEffect> with_test_plausible(std::vector<CandidateEffect> effects, const TestScales& scales) {
  for (auto& e : effects) {
    if (e.plausible_from.empty()) continue;
    const double scale = scales.at(e.plausible_from);
    e.plausible = e.plausible_factor * scale;
    if (!(e.min <= e.plausible && e.plausible <= e.max) || e.plausible == e.neutral)
      throw std::runtime_error(fmt::format(
          "effect '{}': plausible_factor {:g} x {} {:.4g} = {:.4g} {} is {}; change plausible_factor", e.name,
          e.plausible_factor, e.plausible_from, scale, e.plausible, e.unit,
          e.plausible == e.neutral ? "its neutral value" : fmt::format("outside [{:g}, {:g}]", e.min, e.max)));
  }
  return effects;
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
