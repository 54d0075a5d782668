#include "contrast_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "shard/io/json.hpp"
#include "shard/measure/report.hpp"
#include "shard/measure/statistics.hpp"

namespace shard {

namespace fs = std::filesystem;
using namespace measure;

namespace {

// A "no difference" whose test needs a T^2 this many times chi^2's cannot tell: one-rate studies of
// 8 to 12 sets of four specimens (24 to 36 degrees of freedom for 8 components) sit at 1.5-1.9,
// two-rate sets on a pool of 15 at 3.7, on a pool of 9 at 53.
constexpr double kStarvedPool = 2.0;

const CandidateEffect* effect_named(const ContrastReport& r, const std::string& name) {
  return find_effect(r.result.effects, name);
}

// The fitted value of a fit: the confirmed run's value when the decision came from runs,
// otherwise neutral + scale * trial step.
double fitted_value(const ContrastReport& r, const SetDiagnosis& d, std::size_t k) {
  const ContrastFit& f = d.decision.fits[k];
  if (!d.confirmed_values.empty()) return d.confirmed_values[k];
  const CandidateEffect* e = effect_named(r, f.name);
  return e ? e->value_at(f.scale) : 0.0;
}

double fitted_uncertainty(const ContrastReport& r, const SetDiagnosis& d, std::size_t k) {
  const ContrastFit& f = d.decision.fits[k];
  const CandidateEffect* e = effect_named(r, f.name);
  if (!e) return 0;
  // u_scale is in units of the signature's own size: the confirmed run's distance from neutral
  // or the trial step.
  const double unit = d.confirmed_values.empty() ? e->plausible - e->neutral : d.confirmed_values[k] - e->neutral;
  return std::abs(f.u_scale * unit);
}

// A fit that would be named but cannot be told apart on what the contrast spans (a rate effect at
// one rate, a size effect at one size).
std::string unidentifiable_text(const ContrastReport& r, const SetDiagnosis& d, const std::string& name) {
  const CandidateEffect* e = effect_named(r, name);
  if (!e) return fmt::format(" {} would explain it, but it cannot be named on these data.", name);
  return fmt::format(" {} would explain it, but {}.{}", name, e->unidentifiable_reason(d.contrast.coverage),
                     e->separated_by.empty() ? "" : fmt::format(" What would tell: {}.", e->separated_by));
}

// A closest that takes nearly all of the difference away but that these data cannot name: its size
// and share, why it is not named, and what would tell, with no suggestion that it is at work.
std::string unnameable_closest_text(const ContrastReport& r, const SetDiagnosis& d, double share) {
  const ContrastFit& f = d.decision.fits.front();
  const CandidateEffect* e = effect_named(r, f.name);
  return fmt::format(" The closest, {} = {:.4g} +- {:.2g}{}, takes {:.0f} % of it away (T^2 {:.1f} -> chi^2 {:.1f}, "
                     "p = {:.2g} for what remains), but {} cannot be named on these data{}.{}",
                     f.name, fitted_value(r, d, 0), fitted_uncertainty(r, d, 0), e ? e->unit_suffix() : "",
                     100 * share, d.decision.chi_square, f.chi_square, f.p_after, f.name,
                     e ? ": " + e->unidentifiable_reason(d.contrast.coverage) : "",
                     e && !e->separated_by.empty() ? fmt::format(" What would tell: {}.", e->separated_by) : "");
}

// " (named only with 2 loading rates)" after a fit the contrast's data cannot name; "" otherwise.
std::string not_nameable_note(const ContrastReport& r, const SetDiagnosis& d, const ContrastFit& f) {
  if (f.identifiable) return "";
  const CandidateEffect* e = effect_named(r, f.name);
  return e ? fmt::format(" (named only with {})", e->needs_beyond(d.contrast.coverage)) : " (not nameable here)";
}

// What the best pair did: named (the verdict) or tried and left.
std::string pair_text(const ContrastReport& r, const SetDiagnosis& d) {
  const ContrastPairFit& p = *d.pair;
  const CandidateEffect* a = effect_named(r, p.first);
  const CandidateEffect* b = effect_named(r, p.second);
  const auto sized = [](const CandidateEffect* e, double v) { return e ? e->sized(v) : fmt::format("{:.4g}", v); };
  const std::string sizes = fmt::format("{} = {} with {} = {}", p.first, sized(a, d.pair_values[0]), p.second,
                                        sized(b, d.pair_values[1]));
  if (names_a_pair(d))
    return fmt::format(" Two effects at once: {} (simulated together) leave chi^2 {:.1f} (p = {:.2g} for what "
                       "remains); the second's drop from {}'s own chi^2 {:.1f} has p = {:.2g} (level {:.2g}: {} seconds "
                       "tried).{}",
                       sizes, p.chi_square, p.p_after, p.first, p.chi_square + p.drop, p.p_drop,
                       ContrastOptions{}.drop_p / static_cast<double>(std::max<std::size_t>(1, d.seconds_tried)),
                       d.seconds_tried, p.at_bound ? " A size sits at the bound of its range." : "");
  const double level = ContrastOptions{}.drop_p / static_cast<double>(std::max<std::size_t>(1, d.seconds_tried));
  if (p.p_drop < level && p.p_after > ContrastOptions{}.remaining_p)
    return fmt::format(" With a second effect the best pair, {} (simulated together), leaves chi^2 {:.1f} (p = {:.2g} "
                       "for what remains) and the second's drop has p = {:.2g}, but the packing seeds do not agree on "
                       "what the second adds (p = {:.2g} that it is their scatter): a change that redraws the model's "
                       "fracture, not a physics the data ask for. Not named.",
                       sizes, p.chi_square, p.p_after, p.p_drop, p.p_seeds);
  return fmt::format(" With a second effect the best pair, {} (simulated together), leaves chi^2 {:.1f} (p = {:.2g} for "
                     "what remains), the second's drop p = {:.2g} against a level of {:.2g}: not named.",
                     sizes, p.chi_square, p.p_after, p.p_drop, level);
}

// The measurement that would tell whether the lead is the physics at work, on this set's rates.
std::string separating_text(const ContrastReport& r, const SetDiagnosis& d, const std::string& lead) {
  const CandidateEffect* e = effect_named(r, lead);
  const std::string how = e ? e->separating_measurement(d.contrast.coverage) : "";
  return how.empty() ? "" : fmt::format(" What would tell: {}.", how);
}

// How every withheld name's text opens: the set's difference, and the name as its closest.
std::string withheld_opening(const SetDiagnosis& d, const std::string& name) {
  return fmt::format("{} differs from the reference (T^2 = {:.1f}, p = {:.2g}): unexplained difference. The closest, "
                     "{}, explains {:.0f} % of T^2",
                     name, d.decision.chi_square, d.decision.p_value, d.withheld, 100 * d.share);
}

// A rate-independent name for a strength difference that the set's two rates cannot tell from a
// rate-dependent strength (rate_sensitivity.hpp): a lead, with the specimens that would decide.
std::string withheld_for_rate_text(const SetDiagnosis& d, const std::string& name) {
  const RateSensitivity& s = *d.rate_sensitivity;
  const std::string strength = fmt::format(
      "its peak force is {:+.1f} % ({:+.1f} +- {:.1f} % in ln F_max) against the reference at {:g} mm/s, and from {:g} "
      "to {:g} mm/s it changes by {:+.1f} % +- {:.1f} % (95 %) beyond the model's own change, where subcritical crack "
      "growth (n = {:g}) would change it by {:.1f} %",
      100 * std::expm1(s.strength_contrast), 100 * s.strength_contrast, 100 * s.u_strength_contrast, 1e3 * s.slow_rate,
      1e3 * s.slow_rate, 1e3 * s.fast_rate, 100 * s.change, 100 * s.half_width, s.exponent, 100 * s.subcritical);
  const std::string opening =
      withheld_opening(d, name) + " and passes the component and curve tests, but it holds the strength independent of "
                                  "the loading rate, and ";
  if (s.resolved())
    return opening + fmt::format("this set's strength changes with the rate: {}. A rate-independent cause gives no "
                                 "such change, so the set has a rate dependence the name leaves out.",
                                 strength);
  return opening + fmt::format(
      "this set cannot tell: {}. So a strength that grows with the rate explains this set as well. What would tell: "
      "about {} specimens at each rate (now {}), or rates a decade or more apart.",
      strength, s.specimens_needed(), s.specimens_per_rate);
}

// A name withheld because the set carries its own scatter (withhold_names_of_own_scatter): the
// widest of its groups, and what would let the set be tested on its own.
std::string withheld_for_scatter_text(const ContrastReport& r, const SetDiagnosis& d, const std::string& name) {
  const ContrastDiagnosis::GroupScatterLine* widest = nullptr;
  for (const auto& g : r.result.scatter)
    if (g.set == d.set && g.own && (!widest || g.ratio > widest->ratio)) widest = &g;
  const std::size_t specimens = r.sets.sets[d.set].specimens.size();
  const std::string scatter =
      widest ? fmt::format("its {} has {:.3g} x the other sets' variance (p {:.2g})", widest->component,
                           widest->ratio, widest->p_value)
             : std::string("its specimens scatter beyond the other sets'");
  return withheld_opening(d, name) + fmt::format(
      ", but {}, so the set carries its own scatter, estimated from {} specimens: too few to test what "
      "the name leaves unexplained. A scatter that wide is a difference of its own (beams that slide on their "
      "supports, a strength that scatters more, a batch that is not one population), which no shift of the mean "
      "describes: look at this set's curves one by one before you `shard calibrate` this set `--with {}`.",
      scatter, specimens,
      d.withheld.substr(0, d.withheld.find(" + ")));
}

// The specimens that gave no bending strength, one clause each.
std::string invalid_fractures_text(const FractureValidity& v) {
  std::string s = fmt::format("{} of {} specimens gave no bending strength:", v.invalid.size(), v.specimens);
  for (std::size_t k = 0; k < v.invalid.size(); ++k)
    s += fmt::format("{} {} {}", k ? ";" : "", v.invalid[k].specimen, v.invalid[k].reason);
  return s + ".";
}

// A name withheld because half the set or more broke outside the pins or did not break apart.
std::string withheld_for_fractures_text(const SetDiagnosis& d, const std::string& name) {
  return withheld_opening(d, name) + fmt::format(
      ", but {} The bending stress is uniform only between the pins, so its force maximum is not the "
      "material's: check the fixture (rollers that let the beam slide, a pin that bears on a flaw) and test new "
      "specimens before you `shard calibrate` this set `--with {}`.",
      invalid_fractures_text(d.fractures),
      d.withheld.substr(0, d.withheld.find(" + ")));
}

std::string withheld_for_base_text(const ContrastReport& r, const SetDiagnosis& d, const std::string& name) {
  return withheld_opening(d, name) + fmt::format(
      ", but the fitted base leaves NRMSE {:.1f} % against the reference (a name needs at most {:.0f} "
      "%): the effects were moved about a model that is not the reference's specimen. Fit the base first (more "
      "--base-iterations, another --param, a model that does not crush at its rollers), then diagnose again.",
      100 * r.result.calibration.form_error.nrmse,
      100 * ContrastOptions{}.base_nrmse_limit);
}

// A name the component statistics gave and the curve did not bear out: a lead, never a name.
std::string withheld_text(const ContrastReport& r, const SetDiagnosis& d, const std::string& name) {
  if (d.withheld_by == WithheldBy::rate) return withheld_for_rate_text(d, name);
  if (d.withheld_by == WithheldBy::own_scatter) return withheld_for_scatter_text(r, d, name);
  if (d.withheld_by == WithheldBy::fractures) return withheld_for_fractures_text(d, name);
  if (d.withheld_by == WithheldBy::base) return withheld_for_base_text(r, d, name);
  const bool curve_misses = !curve_agrees(d.after);
  std::string why = !improves_on_base(d)
                        ? fmt::format("its simulated contrast curve fits the measured one worse than the base model "
                                      "without it (NRMSE {:.1f} % against {:.1f} %)",
                                      100 * d.after.nrmse, 100 * d.before.nrmse)
                    : curve_misses
                        ? fmt::format("its simulated contrast curve misses the measured one before the peak (NRMSE "
                                      "{:.1f} % against a noise floor of {:.1f} %; a name needs at most {:g}x the floor)",
                                      100 * d.after.rising_nrmse, 100 * naming_floor(d.after),
                                      ContrastOptions{}.curve_floor_factor)
                        : fmt::format("it explains {:.0f} % of the difference (a name needs {:.0f} %)", 100 * d.share,
                                      100 * ContrastOptions{}.min_share);
  return withheld_opening(d, name) +
         fmt::format(" and passes the component tests, but {}: the lab's difference is that physics in another form, "
                     "or another physics. `shard calibrate` this set `--with {}` and look at what remains before "
                     "adding it to the model.",
                     why,
                     d.withheld.substr(0, d.withheld.find(" + "))) +
         separating_text(r, d, d.withheld.substr(0, d.withheld.find(" + ")));
}

// What "no difference" can say: the smallest T^2 the test would have seen, against the same with
// the scatter known. An estimate of few degrees of freedom for its components (a starved pool)
// leaves a test that sees only differences many times larger: then the verdict says so.
std::string power_text(const ContrastReport& r, const SetDiagnosis& d) {
  const double level = ContrastOptions{}.no_difference_p;
  const double k = static_cast<double>(d.contrast.difference.size());
  const double p = static_cast<double>(contrast_component_names().size());
  const double seen = hotelling_critical(level, k, r.result.dof, p);
  const double known = chi_square_critical(level, k);
  const std::string at = fmt::format(" A difference would have been seen from T^2 = {:.3g} on (at {:g}; {:.3g} with the "
                                     "scatter known).", seen, level, known);
  // Fewer degrees of freedom than components: the F test has none left and chi^2 stands in.
  if (r.result.dof - p + 1 >= 1 && seen < kStarvedPool * known) return at;
  return at + fmt::format(" The pooled scatter has {:g} degrees of freedom for {:g} components a rate, which leaves "
                          "the test little power: a smaller difference goes unseen with these specimens. More specimens "
                          "per set, or fewer sets carrying their own scatter, would see it.",
                          r.result.dof, p);
}

// A contrast component taken as the logarithm of a feature (ln_peak_force, ln_stiffness@0.02).
bool is_logarithmic(const std::string& component) { return component.rfind("ln_", 0) == 0; }

// A contrast component in words: ln_peak_force@0.02 is the peak force@0.02.
std::string component_label(const std::string& component) {
  std::string label = is_logarithmic(component) ? component.substr(3) : component;
  std::replace(label.begin(), label.end(), '_', ' ');
  return label;
}

// A contrast component's change as a reader takes it: a ratio for a logarithm, as is otherwise.
std::string component_change_text(const std::string& component, double value) {
  return is_logarithmic(component) ? fmt::format("{:+.1f} %", 100 * std::expm1(value))
                                    : fmt::format("{:+.3f}", value);
}

// The closest effect's model follows the contrast curve before the peak but misses a component a
// name by its curve must reproduce: the data then point at a second cause beside it (a peak force
// it leaves behind) or at another shape of the rising branch.
std::string missed_component_text(const SetDiagnosis& d, const std::string& closest) {
  if (d.after_effect != closest || !curve_agrees(d.after)) return "";
  const auto missed = component_missed_by_curve_name(d.contrast, d.after_components);
  if (!missed) return "";
  const std::string& name = d.contrast.names[*missed];
  const std::string moved = fmt::format(
      " Its model follows the contrast curve before the peak ({:.1f} % against a floor of {:.1f} %) but moves the {} "
      "by {} where the set moved it by {}",
      100 * d.after.rising_nrmse, 100 * naming_floor(d.after), component_label(name),
      component_change_text(name, d.after_components[*missed]), component_change_text(name, d.contrast.difference[*missed]));
  if (is_peak_force_component(name)) return moved + ": a second cause that changes the strength.";
  return moved + ": the set's rising branch bends otherwise than this effect bends it.";
}

std::string verdict_text(const ContrastReport& r, const SetDiagnosis& d) {
  const ContrastDecision& c = d.decision;
  const std::string& name = r.sets.names[d.set];
  if (names_a_pair(d)) {
    std::string rivals;
    for (const auto& rival : c.rivals)
      rivals += fmt::format(" {} explains it almost as well (within {:g} in chi^2): these data cannot tell them apart.",
                            rival, ContrastOptions{}.rival_chi_square);
    return fmt::format("{} differs from the reference (T^2 = {:.1f}, p = {:.2g}) by two effects: the closest single "
                       "one, {}, takes {:.0f} % of it away but leaves p = {:.2g} for what remains.{} `shard calibrate` "
                       "this set `--with {} --with {}` sizes both on the contrast.{}",
                       name, c.chi_square, c.p_value, c.fits.front().name,
                       c.chi_square > 0 ? 100 * c.fits.front().drop / c.chi_square : 0.0, c.fits.front().p_after,
                       pair_text(r, d), d.pair->first, d.pair->second, rivals);
  }
  if (c.verdict == kNoDifference)
    return fmt::format("{} does not differ from the reference beyond the specimens' scatter (Hotelling T^2 = {:.1f}, "
                       "p = {:.2g}); no library effect's contrast is significant.{}",
                       name, c.chi_square, c.p_value, power_text(r, d));
  if (c.verdict == kUnexplainedDifference && !d.withheld.empty())
    return withheld_text(r, d, name);
  if (c.verdict == kUnexplainedDifference) {
    std::string s = fmt::format("{} differs from the reference (T^2 = {:.1f}, p = {:.2g}), and no library effect "
                                "explains the difference.",
                                name, c.chi_square, c.p_value);
    std::string unnameable_said;  // the closest's text already says why it is not named
    if (!c.fits.empty()) {
      const ContrastFit& f = c.fits.front();
      const double share = c.chi_square > 0 ? f.drop / c.chi_square : 0;
      // A fit that takes nearly all of a significant difference away is a lead, not a miss: on
      // foreign truth a right effect in the lab's own form (a parabolic softening against the
      // library's linear one) took 90-93 % of T^2, the wrong closest fits 16-78 %: hence 85 %.
      // The verdict stays; the text points at the effect.
      const bool lead = share >= 0.85 && f.p_drop < 0.01;
      if (lead && !f.identifiable) {
        s += unnameable_closest_text(r, d, share);
        unnameable_said = f.name;
      } else if (lead) {
        const CandidateEffect* e = effect_named(r, f.name);
        s += fmt::format(" The closest, {} = {:.4g} +- {:.2g}{}, takes {:.0f} % of it away (T^2 {:.1f} -> chi^2 "
                         "{:.1f}, the drop has p = {:.2g}) but leaves p = {:.2g} for what remains: {} in another form "
                         "than the library's, or {} and a second difference. `shard calibrate` this set `--with {}` and "
                         "look at what remains; a difference the library lacks is added as a plugin parameter with a "
                         "neutral value (shard new-plugin, docs/how-to/write-a-plugin.md) and an [[effect]] entry.",
                         f.name, fitted_value(r, d, 0), fitted_uncertainty(r, d, 0), e ? e->unit_suffix() : "", 100 * share,
                         c.chi_square, f.chi_square, f.p_drop, f.p_after, f.name, f.name, f.name);
        s += missed_component_text(d, f.name);
      } else {
        // Simulated at its fitted size, the closest can fit worse than no effect at all.
        const std::string took =
            share > 0 ? fmt::format("takes {:.0f} % of it away and leaves", 100 * share) : "takes none of it away: it leaves";
        s += fmt::format(" The closest, {}, {} chi^2 {:.1f} (p = {:.2g} for what "
                         "remains): no library effect in the library's form explains it. The difference is physics "
                         "the library lacks, or one of its effects in a form of the lab's; a missing one is added as "
                         "a plugin parameter with a neutral value (shard new-plugin, docs/how-to/write-a-plugin.md) "
                         "and an [[effect]] entry, then diagnosed again.",
                         f.name, took, f.chi_square, f.p_after);
      }
    }
    if (d.pair) s += pair_text(r, d);
    if (!c.unidentifiable.empty() && c.unidentifiable != unnameable_said)
      s += unidentifiable_text(r, d, c.unidentifiable);
    return s;
  }
  const CandidateEffect* e = effect_named(r, c.verdict);
  std::string s = fmt::format("{} differs from the reference (T^2 = {:.1f}, p = {:.2g}) by {}: {} = {:.4g} +- {:.2g}{} "
                              "leaves chi^2 {:.1f} (p = {:.2g} for what remains; the drop has p = {:.2g}).",
                              name, c.chi_square, c.p_value, c.verdict, e ? e->parameter : c.verdict,
                              fitted_value(r, d, 0), fitted_uncertainty(r, d, 0), e ? e->unit_suffix() : "",
                              c.fits.front().chi_square, c.fits.front().p_after, c.fits.front().p_drop);
  if (c.fits.front().at_bound) s += " The size sits at the bound of its physical range.";
  if (d.named_by_curve)
    s += fmt::format(" The components at and after the peak differ beyond noise, so the name rests on the contrast "
                     "curve, which the model reproduces before the peak ({:.1f} % against a floor of {:.1f} %), and on "
                     "the {:.0f} % of T^2 it explains: the lab's crack runs in another form than the model's.",
                     100 * d.after.rising_nrmse, 100 * naming_floor(d.after), 100 * d.share);
  for (const auto& rival : c.rivals) {
    const CandidateEffect* x = effect_named(r, rival);
    s += fmt::format(" {} explains it almost as well (within {:g} in chi^2): these data cannot tell them apart{}.", rival,
                     ContrastOptions{}.rival_chi_square,
                     x && !x->separated_by.empty() ? fmt::format("; {} would", x->separated_by) : "");
  }
  return s;
}

// What the verdicts rest on: each moved base assumption, per set with a model shown.
std::string assumptions_markdown(const ContrastReport& r) {
  bool any = false;
  for (const auto& d : r.result.sets) any = any || !d.assumptions.empty();
  if (!any)
    return "\nBase assumptions not checked: the base model holds the scene's roller friction, damping, gravity and "
           "grain size. To see how much each verdict leans on one, move it with --assumption section.key=value "
           "(e.g. --assumption simulation.global_damping=0.1): the base and each set's shown model are run again "
           "there.\n";
  std::string md =
      "\n## What the verdicts rest on\n\nEach base assumption moved in turn, the shown model (named, or the closest) "
      "run again on the moved base at its confirmed size. Size needed: the effect size the measured contrast asks "
      "for there, per the size it asks for on the base (1: the verdict does not lean on the assumption). A name "
      "holds when the curve still agrees within 1.5x its floor.\n\n| set | model shown | assumption | size needed | "
      "contrast NRMSE | before the peak / floor | name holds |\n|---|---|---|---|---|---|---|\n";
  for (const auto& d : r.result.sets)
    for (const auto& a : d.assumptions)
      md += fmt::format("| {} | {} | {} | {:.2f} x | {:.2f} % (base: {:.2f} %) | {:.2f} % / {:.2f} % | {} |\n",
                        r.sets.names[d.set], d.after_effect, a.assumption, a.size_ratio, 100 * a.after.nrmse,
                        100 * d.after.nrmse, 100 * a.after.rising_nrmse, 100 * naming_floor(a.after),
                        a.curve_agrees ? "yes" : "no");
  return md;
}

std::string group_name(const ContrastReport& r, const ContrastDiagnosis::GroupScatterLine& g) {
  return fmt::format("{} at {:g} mm/s", r.sets.names[g.set], 1e3 * g.rate);
}

// The scatter the contrasts are weighed with, and the sets that carry their own.
std::string scatter_markdown(const ContrastReport& r) {
  const auto& lines = r.result.scatter;
  const auto widest = std::max_element(lines.begin(), lines.end(), [](auto& a, auto& b) { return a.ratio < b.ratio; });
  const bool any_own = std::any_of(lines.begin(), lines.end(), [](auto& g) { return g.own; });
  if (!any_own)
    return widest == lines.end()
               ? fmt::format("Specimen scatter pooled over all sets ({:g} degrees of freedom).\n\n", r.result.dof)
               : fmt::format("Specimen scatter pooled over all sets ({:g} degrees of freedom); the widest, {}, has a "
                             "{} variance {:.2f} x the others' (p {:.2g}; --own-scatter sets such a set apart).\n\n",
                             r.result.dof, group_name(r, *widest), widest->component, widest->ratio, widest->p_value);
  std::string md = fmt::format(
      "Specimen scatter pooled over the sets that scatter alike ({:g} degrees of freedom). These scatter beyond the "
      "others and carry their own (their contrasts are weighed with it: it lowers their T^2 and their remainders alike):\n\n"
      "| set | widest component | its variance against the others' | p |\n| --- | --- | --- | --- |\n",
      r.result.dof);
  for (const auto& g : lines)
    if (g.own) md += fmt::format("| {} | {} | {:.2f} x | {:.2g} |\n", group_name(r, g), g.component, g.ratio, g.p_value);
  return md + "\n";
}

std::string regimes_markdown(const Comparison& c) {
  std::string md = "| regime | mean residual | force error |\n|---|---|---|\n";
  for (const auto& g : c.regimes)
    if (g.points() > 0)
      md += fmt::format("| {} | {:+.2f} | {:+.1f} % |\n", regime_name(g.regime), g.mean_residual, 100 * g.relative_error);
  return md;
}

// The form error at a finer packing: does resolution explain it?
std::string finer_markdown(const ContrastReport& r) {
  const Comparison& fe = r.result.calibration.form_error;
  const Comparison& ff = r.result.finer->form_error;
  std::string md = fmt::format("\nAt diameters x {:g} (the base fitted again: ", r.result.finer_factor);
  for (std::size_t k = 0; k < r.result.finer->keys.size(); ++k)
    md += fmt::format("{}{}={:.4g}", k ? ", " : "", r.result.finer->keys[k], r.result.finer->values[k]);
  md += fmt::format(") the form error is NRMSE {:.1f} % against {:.1f} %: ", 100 * ff.nrmse, 100 * fe.nrmse);
  // A third less is more than the packing noise of a few seeds moves an NRMSE (tiny beam: 5-7 %).
  md += ff.nrmse < 2.0 / 3.0 * fe.nrmse
            ? "resolution explains much of it; a finer model packing is worth its cost.\n"
            : "resolution does not explain it; it comes from the form of the laws or the fixture, and the contrasts "
              "below are what can be trusted.\n";
  // Which regimes and features stay beyond noise at the finer packing (the same verdict as above).
  md += fmt::format("\nAt diameters x {:g}: {}\n\n", r.result.finer_factor, ff.verdict);
  return md + regimes_markdown(ff);
}

// The base fit's path, values and form error against the reference (and at a finer packing).
std::string base_markdown(const ContrastReport& r) {
  std::string md = "## The base model and its form error\n\n";
  if (r.result.calibration.keys.empty())
    md += "Base parameters as in the scene (no --param given).\n\n";
  else {
    for (std::size_t k = 0; k < r.result.calibration.path.size(); ++k) md += fmt::format("{}. {}\n", k + 1, r.result.calibration.path[k]);
    const BaseCalibration& c = r.result.calibration;
    if (c.returned_line + 1 < c.path.size())
      md += fmt::format("\nThe base is line {}'s: the steps after it raised the misfit beyond the runs' noise and "
                        "were halved back without reaching a better point.\n",
                        c.returned_line + 1);
    md += fmt::format("\nFitted to {}:", c.form_targets ? "the reference's stiffness, peak force, peak displacement and "
                                                          "post-peak regime"
                                                        : "the reference's stiffness, peak force and peak displacement");
    for (std::size_t k = 0; k < c.keys.size(); ++k) {
      md += fmt::format("{}{} = {:.4g} +- {:.2g}", k ? "; " : " ", c.keys[k], c.values[k], c.uncertainty[k]);
      if (c.at_range_bound[k])
        md += fmt::format(" (at the bound of its range [{:g}, {:g}]: the data ask for more than the plugin accepts)",
                          c.range[k].min, c.range[k].max);
    }
    md += " (uncertainties from the reference's specimen scatter through the last Gauss-Newton step).\n";
    for (const auto& key : r.result.calibration.at_bound)
      md += fmt::format("\n{}'s last step was clamped to a factor of 2: the base fit did not converge in the "
                        "iterations given (--base-iterations).\n",
                        key);
  }
  const Comparison& fe = r.result.calibration.form_error;
  md += fmt::format("\nAgainst the reference the fitted base model leaves NRMSE {:.1f} %: {}\n\n", 100 * fe.nrmse, fe.verdict);
  md += regimes_markdown(fe);
  if (!r.result.reference_fractures.invalid.empty())
    md += fmt::format("\nThe reference's fractures: {} The base is fitted to them all: test new specimens where "
                      "these are many.\n",
                      invalid_fractures_text(r.result.reference_fractures));
  if (r.result.finer) md += finer_markdown(r);
  return md + "\nThis form error is common to sets tested with one fixture; it cancels in the contrasts below.\n\n";
}

// One line a set: T^2, the verdict, its value, the share explained and the curve rule's figures.
std::string verdicts_markdown(const ContrastReport& r) {
  std::string md;
  md += "## Verdicts\n\n| set | T^2 | p (no difference) | verdict | value | share of T^2 | contrast NRMSE: base -> with "
        "effect | before the peak: with effect / floor |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& d : r.result.sets) {
    const ContrastDecision& c = d.decision;
    const bool named = c.verdict != kNoDifference && c.verdict != kUnexplainedDifference;
    const CandidateEffect* e = named ? effect_named(r, c.verdict) : nullptr;
    std::string value = "-";
    if (names_a_pair(d))
      value = fmt::format("{:.4g}; {:.4g}", d.pair_values[0], d.pair_values[1]);
    else if (named)
      value = fmt::format("{:.4g} +- {:.2g}{}", fitted_value(r, d, 0), fitted_uncertainty(r, d, 0), e ? e->unit_suffix() : "");
    const std::string verdict = d.withheld.empty() ? c.verdict : fmt::format("{} (closest: {})", c.verdict, d.withheld);
    md += fmt::format("| {} | {:.1f} | {:.2g} | {} | {} | {:.0f} % | {:.2f} % -> {} | {} |\n", r.sets.names[d.set],
                      c.chi_square, c.p_value, verdict, value, 100 * d.share, 100 * d.before.nrmse,
                      d.after_effect.empty() ? "-" : fmt::format("{:.2f} % ({})", 100 * d.after.nrmse, d.after_effect),
                      d.after_effect.empty()
                          ? "-"
                          : fmt::format("{:.2f} % / {:.2f} %", 100 * d.after.rising_nrmse, 100 * naming_floor(d.after)));
  }
  md += "\nContrast NRMSE: RMS difference between the measured contrast curve (set mean - reference mean) and the "
        "model's, over the displacement range both cover, in units of the reference's peak force. Before the peak: the "
        "same over the rising branch, against its noise floor (the measured contrast's standard uncertainty and the "
        "simulated contrast's packing scatter); a name needs at most 1.5x the floor there and half of T^2 explained.\n";
  return md;
}

// A section a set: the components measured and modelled, and every effect's fit.
std::string set_sections_markdown(const ContrastReport& r) {
  std::string md;
  for (const auto& d : r.result.sets) {
    md += fmt::format("\n## {}\n\n{}\n\n", r.sets.names[d.set], verdict_text(r, d));
    if (!d.fractures.invalid.empty() && d.withheld_by != WithheldBy::fractures)
      md += fmt::format("Fractures: {} Their force maxima are in the set's mean.\n\n", invalid_fractures_text(d.fractures));
    const bool shown = !d.after_components.empty();
    md += fmt::format("| component | measured difference | u |{}\n|---|---|---|{}\n",
                      !shown ? ""
                      : names_a_pair(d)
                          ? fmt::format(" model with {} = {:.4g}, {} = {:.4g} | (model - measured) / u |", d.pair->first,
                                        d.pair_values[0], d.pair->second, d.pair_values[1])
                          : fmt::format(" model with {} = {:.4g} | (model - measured) / u |", d.after_effect, d.after_value),
                      shown ? "---|---|" : "");
    const std::vector<double> uncertainties = component_uncertainties(d.contrast);
    for (std::size_t i = 0; i < d.contrast.names.size(); ++i) {
      const double u = uncertainties[i];
      md += fmt::format("| {} | {:+.4g} | {:.2g} |{}\n", d.contrast.names[i], d.contrast.difference[i], u,
                        shown ? fmt::format(" {:+.4g} | {:+.1f} |", d.after_components[i],
                                            (d.after_components[i] - d.contrast.difference[i]) / u)
                              : "");
    }
    md += fmt::format("\n{} | size | +- | chi^2 after | drop | p of the drop | chi^2 within the form tolerance | p after | at bound |\n"
                      "|---|---|---|---|---|---|---|---|---|\n",
                      d.confirmed_values.empty() ? "| effect (linear, from the signatures)" : "| effect (simulated at its size)");
    for (std::size_t k = 0; k < d.decision.fits.size(); ++k) {
      const ContrastFit& f = d.decision.fits[k];
      md += fmt::format("| {}{} | {:.4g} | {:.2g} | {:.1f} | {:.1f} | {:.2g} | {:.1f} | {:.2g} | {} |\n", f.name,
                        not_nameable_note(r, d, f),
                        fitted_value(r, d, k), fitted_uncertainty(r, d, k), f.chi_square, f.drop, f.p_drop,
                        f.chi_square_form, f.p_after, f.at_bound ? "yes" : "");
    }
  }
  return md;
}

std::string left_out_markdown(const std::vector<ContrastDiagnosis::LeftOutEffect>& left_out) {
  if (left_out.empty()) return {};
  std::string md = "Left out of the library (their trials gave no contrast to read, so no set is held against "
                   "them; a set they would explain reads \"unexplained difference\"):\n\n";
  for (const auto& e : left_out) md += fmt::format("- {}: {}\n", e.name, e.reason);
  return md + "\n";
}

}  // namespace

std::string contrast_markdown(const ContrastReport& r) {
  const auto& names = contrast_component_names();
  std::string md = fmt::format("# Contrast diagnosis: {} sets against {}\n\n", r.sets.sets.size(),
                               r.sets.reference ? "the reference " + r.sets.names[*r.sets.reference]
                                                : std::string("the consensus of the others"));
  md += fmt::format("Components per curve: {}. Effects tried: {}.\n\n", fmt::join(names, ", "),
                    r.result.effects.size());
  md += left_out_markdown(r.result.left_out);
  md += scatter_markdown(r);
  if (!r.result.scaled_sizes.empty())
    md += "Trial sizes from the fitted base run (plausible_from rules, docs/explanation/diagnosis.md):\n\n```\n" + r.result.scaled_sizes +
          "```\n\n";
  md += base_markdown(r) + verdicts_markdown(r) + set_sections_markdown(r);
  md += assumptions_markdown(r);
  md += fmt::format("\nLargest kinetic/elastic energy ratio before breakage (deformation, less the rigid-body motion): "
                    "{:.2g} over the base and the effects at their fitted sizes; {:.2g} over the effects' trials at their "
                    "library sizes (not judged: a probe, not a model of the data).\n",
                    r.result.health.max_kinetic_to_elastic, r.result.health.max_probe_kinetic_to_elastic);
  if (!r.result.health.dynamic_warning.empty()) md += "\n" + r.result.health.dynamic_warning + "\n";
  return md;
}

namespace {

// diagnose.json's format: raise it when a key changes meaning or disappears.
constexpr int kDiagnoseFormatVersion = 2;

io::Json base_json(const BaseCalibration& c) {
  io::Json values = io::Json::object(), uncertainty = io::Json::object(), at_bound = io::Json::array();
  for (std::size_t k = 0; k < c.keys.size(); ++k) {
    values[c.keys[k]] = c.values[k];
    uncertainty[c.keys[k]] = c.uncertainty[k];
    if (c.at_range_bound[k]) at_bound.push_back(c.keys[k]);
  }
  return {{"base", values}, {"base_uncertainty", uncertainty}, {"base_at_range_bound", at_bound},
          {"base_form_targets", c.form_targets}, {"base_path", c.path}, {"base_returned_line", c.returned_line + 1}};
}

io::Json fits_json(const ContrastReport& r, const SetDiagnosis& d) {
  io::Json fits = io::Json::array();
  for (std::size_t k = 0; k < d.decision.fits.size(); ++k) {
    const ContrastFit& f = d.decision.fits[k];
    fits.push_back({{"name", f.name}, {"value", fitted_value(r, d, k)}, {"u_value", fitted_uncertainty(r, d, k)},
                    {"chi_square", f.chi_square}, {"p_drop", f.p_drop}, {"p_after", f.p_after},
                    {"at_bound", f.at_bound}, {"identifiable", f.identifiable}});
  }
  return fits;
}

io::Json pair_json(const SetDiagnosis& d) {
  if (!d.pair) return nullptr;
  return {{"first", d.pair->first},          {"second", d.pair->second},
          {"values", {d.pair_values[0], d.pair_values[1]}},
          {"chi_square", d.pair->chi_square}, {"p_drop", d.pair->p_drop},
          {"p_after", d.pair->p_after},       {"p_seeds", d.pair->p_seeds},
          {"seconds_tried", d.seconds_tried},
          {"at_bound", d.pair->at_bound},     {"named", names_a_pair(d)}};
}

io::Json assumptions_json(const SetDiagnosis& d) {
  io::Json out = io::Json::array();
  for (const auto& a : d.assumptions)
    out.push_back({{"assumption", a.assumption},
                   {"size_ratio", a.size_ratio},
                   {"nrmse_effect", a.after.nrmse},
                   {"rising_nrmse_effect", a.after.rising_nrmse},
                   {"rising_nrmse_floor", naming_floor(a.after)},
                   {"curve_agrees", a.curve_agrees}});
  return out;
}

const char* withheld_by_name(WithheldBy by) {
  switch (by) {
    case WithheldBy::curve: return "curve";
    case WithheldBy::rate: return "rate";
    case WithheldBy::own_scatter: return "own_scatter";
    case WithheldBy::fractures: return "fractures";
    case WithheldBy::base: return "base";
  }
  return "";
}

io::Json rate_sensitivity_json(const SetDiagnosis& d) {
  if (!d.rate_sensitivity) return nullptr;
  const RateSensitivity& s = *d.rate_sensitivity;
  return {{"slow_rate", s.slow_rate},
          {"fast_rate", s.fast_rate},
          {"strength_contrast", s.strength_contrast},
          {"u_strength_contrast", s.u_strength_contrast},
          {"change", s.change},
          {"u_change", s.u_change},
          {"dof", s.dof},
          {"half_width", s.half_width},
          {"subcritical_change", s.subcritical},
          {"subcritical_exponent", s.exponent},
          {"resolved", s.resolved()},
          {"specimens_per_rate", s.specimens_per_rate},
          {"specimens_needed", s.specimens_needed()}};
}

io::Json fractures_json(const FractureValidity& v) {
  io::Json j = io::Json::array();
  for (const auto& f : v.invalid) j.push_back({{"specimen", f.specimen}, {"reason", f.reason}});
  return j;
}

io::Json set_json(const ContrastReport& r, const SetDiagnosis& d) {
  const ContrastDecision& c = d.decision;
  const bool shown = !d.after_effect.empty();
  return {{"name", r.sets.names[d.set]},
          {"t_square", c.chi_square},
          {"p_value", c.p_value},
          {"verdict", c.verdict},
          {"withheld", d.withheld},
          {"withheld_by", d.withheld.empty() ? "" : withheld_by_name(d.withheld_by)},
          {"named_by_curve", d.named_by_curve},
          {"share_explained", d.share},
          {"nrmse_base", d.before.nrmse},
          {"nrmse_effect", shown ? d.after.nrmse : d.before.nrmse},
          {"nrmse_floor", shown ? d.after.floor : d.before.floor},
          {"rising_nrmse_base", d.before.rising_nrmse},
          {"rising_nrmse_effect", shown ? d.after.rising_nrmse : d.before.rising_nrmse},
          {"rising_nrmse_floor", shown ? naming_floor(d.after) : naming_floor(d.before)},
          {"effect_shown", d.after_effect},
          {"fits", fits_json(r, d)},
          {"pair", pair_json(d)},
          {"unidentifiable", c.unidentifiable},
          {"rivals", c.rivals},
          {"rate_sensitivity", rate_sensitivity_json(d)},
          {"assumptions", assumptions_json(d)},
          {"invalid_fractures", fractures_json(d.fractures)}};
}

}  // namespace

io::Json contrast_json(const ContrastReport& r) {
  io::Json j = io::json_document(kDiagnoseFormatVersion);
  j["reference"] = r.sets.reference ? r.sets.names[*r.sets.reference] : "";
  j["dof"] = r.result.dof;
  j["scatter"] = io::Json::array();
  for (const auto& g : r.result.scatter)
    j["scatter"].push_back({{"set", r.sets.names[g.set]}, {"rate", g.rate}, {"ratio", g.ratio}, {"component", g.component}, {"p_value", g.p_value},
                            {"own", g.own}});
  j["form_error_nrmse"] = r.result.calibration.form_error.nrmse;
  j.update(base_json(r.result.calibration));
  j["dynamic_warning"] = r.result.health.dynamic_warning;
  j["left_out_effects"] = io::Json::array();
  for (const auto& e : r.result.left_out) j["left_out_effects"].push_back({{"effect", e.name}, {"reason", e.reason}});
  j["reference_invalid_fractures"] = fractures_json(r.result.reference_fractures);
  j["sets"] = io::Json::array();
  for (const auto& d : r.result.sets) j["sets"].push_back(set_json(r, d));
  return j;
}

void plot_contrasts(const ContrastReport& r, const fs::path& image) {
  const fs::path dat = fs::path(image).replace_extension(".dat"), gp = fs::path(image).replace_extension(".gp");
  {
    std::ofstream out(dat);
    for (const auto& d : r.result.sets) {
      out << "# " << r.sets.names[d.set] << "\n# xi measured u base effect\n";
      for (std::size_t k = 0; k < d.before.xi.size(); ++k)
        out << fmt::format("{:.6g} {:.6g} {:.6g} {:.6g} {:.6g}\n", d.before.xi[k], d.before.measured[k],
                           d.before.u_measured[k], d.before.simulated[k],
                           d.after_effect.empty() ? d.before.simulated[k] : d.after.simulated[k]);
      out << "\n\n";
    }
  }
  const std::size_t n = r.result.sets.size();
  std::string script = fmt::format(
      "set terminal pngcairo noenhanced size 900,{} font ',9'\nset output '{}'\nset multiplot layout {},1\n"
      "set xlabel 'w / w_ref'\nset ylabel 'dF / F_ref'\nset grid\nset key outside right\n",
      std::max<std::size_t>(300, 260 * n), image.string(), n);
  for (std::size_t s = 0; s < n; ++s) {
    const SetDiagnosis& d = r.result.sets[s];
    script += fmt::format("set title '{}: {}'\n", r.sets.names[d.set], d.decision.verdict);
    script += fmt::format(
        "plot '{0}' index {1} using 1:($2-2*$3):($2+2*$3) with filledcurves lc rgb '#cfe0f0' title 'measured +-2u', "
        "'' index {1} using 1:2 with lines lw 2 lc rgb '#1f4e79' title 'measured', "
        "'' index {1} using 1:4 with lines dt 2 lc rgb '#888888' title 'base model'{2}\n",
        dat.string(), s,
        d.after_effect.empty()
            ? std::string()
            : fmt::format(", '' index {} using 1:5 with lines lw 2 lc rgb '#c0392b' title 'with {}'", s, d.after_effect));
  }
  script += "unset multiplot\n";
  std::ofstream(gp) << script;
  if (run_program("gnuplot", {gp.string()}) != 0)
    throw std::runtime_error(fmt::format("gnuplot failed on {} (is gnuplot installed?)", gp.string()));
}

}  // namespace shard
