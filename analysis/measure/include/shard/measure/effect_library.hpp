#pragma once
// The candidate effects `shard diagnose` tries (scenes/measurements/effects.toml): each is one
// parameter with a neutral value (the effect is off, the base model) and a plausible size (the
// trial run that gives its signature). `set` holds what the effect needs besides its parameter,
// such as the plugin that carries it;
// `machine_compliance` is not a scene key but the series spring of the testing machine, applied
// to the simulated curve (w + C F).
//
//   [[effect]]
//   name = "bond_viscosity"
//   parameter = "bond.damping"        # section.key, wall.NAME.key, or machine_compliance
//   unit = "N s/m"
//   neutral = 0.0                     # left out for a plugin parameter: its schema's neutral
//   plausible = 0.02
//   set = []                          # e.g. ["contact.plugin=linear_spring"]
//   separated_by = "a second loading rate"
//   doc = "viscous bond force on the strain rate: a rate-dependent stiffness and strength"
//
// A plausible size that follows from the test rather than from one beam: `plausible_from` names a
// scale of the measurements and `plausible_factor` multiplies it (plausible = factor x scale, in
// the parameter's unit, replacing `plausible`):
//   time_to_peak        s, the shortest mean time from the first reading to F_max over the loading
//                       rates (model time: divided by --time-compression); a viscosity shows when
//                       its time is a fraction of it
//   peak_force          N, mean F_max
//   peak_displacement   m, mean w at F_max
//   secant_compliance   m/N, w_peak / F_max: a machine compliance is a fraction of the specimen's
//   e.g.  plausible_from = "time_to_peak"   plausible_factor = 0.1
// A rate effect (a viscosity) changes a curve at one loading rate only in its shape, which
// rate-independent effects (softening, asymmetry) also change: `rates_needed = 2` says that the
// data need that many loading rates before the effect can be told apart and named. With fewer, a
// diagnosis still scores, refits and reports it (a rival, with the caveat), never names it.
// `sizes_needed = 2` says the same of specimen sizes: a bond strength scatter lowers the strength
// of one specimen size as any other weakening does (a self-weight, a weaker batch); what is its
// own is the Weibull size effect, the larger specimen the weaker.
// A parameter that is not a plain number in the scene (a vector such as simulation.gravity) takes
// `value_format = "[0.0, 0.0, {}]"`: the effect's scalar value goes where {} stands.
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "shard/measure/measurements.hpp"

namespace shard::measure {

inline constexpr const char* kMachineCompliance = "machine_compliance";

// What the data span that an effect may need before it can be told from its look-alikes.
struct DataCoverage {
  std::size_t rates = 1;  // distinct loading rates
  // Specimen sizes the diagnosis compares: one scene, one geometry (a set of other specimens is
  // refused or, with --ignore-geometry, simulated at the scene's size).
  std::size_t sizes = 1;
};

struct CandidateEffect {
  std::string name;
  std::string parameter;
  std::string unit;
  double neutral = 0;
  double plausible = 0;
  std::vector<std::string> set;  // extra overrides the effect needs whenever it is on
  std::string separated_by;      // the measurement that tells it apart from look-alikes
  std::string doc;
  std::string value_format;      // "" or a scene value with one {} for the scalar, e.g. "[0, 0, {}]"
  // The parameter's physical range (keys min, max): a diagnosis does not ask for a value outside.
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  std::string plausible_from;  // "" or a scale of the measurements (above)
  double plausible_factor = 0;
  int rates_needed = 1;  // loading rates the data need before the effect can be named (above)
  int sizes_needed = 1;  // specimen sizes the same (above)
  std::string origin;    // "file:line:column" of its [[effect]] table, for messages

  // Can the effect be told apart on data that span `data`?
  bool identifiable_at(const DataCoverage& data) const { return !lacks_rates(data) && !lacks_sizes(data); }
  bool lacks_rates(const DataCoverage& data) const { return data.rates < static_cast<std::size_t>(rates_needed); }
  bool lacks_sizes(const DataCoverage& data) const { return data.sizes < static_cast<std::size_t>(sizes_needed); }
  // What it needs that `data` lack, "2 loading rates" or "2 specimen sizes" ("" when nothing).
  std::string needs_beyond(const DataCoverage& data) const;
  // Why it cannot be named on `data`, in a report's words ("" when it can): what it needs, and why.
  std::string unidentifiable_reason(const DataCoverage& data) const;
  // The measurement that would tell this effect from its rivals on `data`: separated_by, except for
  // a rate effect on data that already have the rates it needs.
  std::string separating_measurement(const DataCoverage& data) const;

  bool post_processing() const { return parameter == kMachineCompliance; }
  // The plugin this effect switches its section to ("crushing_bond" for set = ["bond.plugin=
  // crushing_bond"] and section "bond"), or "" when it keeps the scene's.
  std::string plugin_set_for(const std::string& section) const;
  // The overrides that put the effect at `value` into a scene (none for machine compliance).
  std::vector<std::string> overrides(double value) const;
  // The scene's text for the parameter at `value` (value_format applied).
  std::string scene_value(double value) const;
  // `value` to four digits with its unit as a report prints it: "4.87e-05 m/N", and "2" for a
  // dimensionless ratio (unit "1").
  std::string sized(double value) const;
  // " m/N" to follow a number; "" for a dimensionless ratio.
  std::string unit_suffix() const;
  // [min, max] as multiples of the trial step plausible - neutral, from neutral.
  double scale_min() const;
  double scale_max() const;
  // The value `scale` trial steps from neutral, kept inside [min, max]: a linear step or an
  // optimiser's bound must not ask a plugin for a negative friction (the run fails and the effect
  // drops out of the diagnosis), and at the bound neutral + scale * step can round past it.
  double value_at(double scale) const;
};

// Can the two effects be on in one model? Not when one switches a section's plugin (its `set`)
// that the other's parameter belongs to under another plugin, or both switch one section to
// different plugins: a crushing bond law has no compression ratio of the beam bond's.
bool combinable(const CandidateEffect& a, const CandidateEffect& b);

// The neutral value a plugin's schema declares for a scene parameter "section.key", if any.
using SchemaNeutral = std::function<std::optional<double>(const std::string& parameter)>;

// The neutrals of the plugins on the default search path (SHARD_PLUGIN_PATH, the build tree's
// and the installed plugin folders): for bond.KEY and contact.KEY the neutral value every bond
// (contact) plugin declaring KEY declares; none when no plugin declares one; throws when two
// plugins declare different ones (the library entry must then give `neutral` itself).
SchemaNeutral plugin_schema_neutrals();

// The range a scene parameter may take: for bond.KEY and contact.KEY the tightest [min, max] over
// every bond (contact) plugin on the default search path (and `extra_dirs`) declaring KEY
// (ParamSpec); unbounded for other keys or when no plugin declares it. What a base fit may ask of
// a parameter (bond.poisson_ratio <= 0.5).
struct ParameterRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};
ParameterRange plugin_parameter_range(const std::string& parameter,
                                      const std::vector<std::filesystem::path>& extra_dirs = {});

// The effect of that name among `effects`; nullptr when there is none.
const CandidateEffect* find_effect(const std::vector<CandidateEffect>& effects, const std::string& name);

// Reads the library; errors name the file, line and column. An entry for a plugin parameter
// leaves out `neutral`: it is the one the plugin's schema declares (`schema`), so that a neutral
// value is declared once, in the policy's schema. An entry that gives a `neutral` the schema
// contradicts is refused.
std::vector<CandidateEffect> read_effect_library(const std::filesystem::path& file,
                                                 const SchemaNeutral& schema = plugin_schema_neutrals());

// The scales of a measurement set a plausible_from rule refers to.
struct TestScales {
  double time_to_peak = 0, peak_force = 0, peak_displacement = 0, secant_compliance = 0;
  double at(const std::string& name) const;  // throws for an unknown name, listing the valid ones
};
inline constexpr const char* kTestScaleNames = "time_to_peak, peak_force, peak_displacement, secant_compliance";
// Specimens grouped by loading rate; time_compression: the model runs that many times faster.
TestScales test_scales(const std::vector<std::vector<Specimen>>& rate_groups, double time_compression = 1);

// The effects with every plausible_from rule applied. Throws, naming the effect, when the size is
// outside [min, max] or equals neutral.
std::vector<CandidateEffect> with_test_plausible(std::vector<CandidateEffect> effects, const TestScales& scales);

// The library entries named in `names` (all when empty); an unknown name lists the valid ones.
std::vector<CandidateEffect> select_effects(const std::vector<CandidateEffect>& library,
                                            const std::vector<std::string>& names);

}  // namespace shard::measure
