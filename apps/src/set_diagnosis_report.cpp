#include "set_diagnosis_report.hpp"

#include <fmt/format.h>

#include <cmath>

namespace shard {
namespace {

using namespace measure;

// diagnose.json's format (single-set form): raise it when a key changes meaning or disappears.
constexpr int kDiagnoseFormatVersion = 1;

std::string join(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

std::string values_text(const std::vector<std::string>& keys, const StepModel& m) {
  std::string v;
  for (std::size_t i = 0; i < keys.size(); ++i) v += fmt::format("{}{}={:.4g}", v.empty() ? "" : ", ", keys[i], m.parameters[i]);
  for (const auto& [e, x] : m.kept) v += fmt::format(", {}={:.4g}", e->name, x);
  return v;
}

std::string scoring_text(Scoring scoring) {
  if (scoring == Scoring::FrozenBand) return "Every run is scored against the base model's simulated band.";
  if (scoring == Scoring::Likelihood)
    return "The refits' chi^2 carry the likelihood's log-variance term against the base model's band.";
  return "A refit whose NRMSE rises above the base refit's is neither named nor kept, whatever its chi^2 (a wider "
         "band must not pass for a better model).";
}

// What measurements would tell `a` and `b` apart (the library's separated_by, or the usual ones).
std::string separating_text(const SetDiagnosisResult& d, const std::string& a, const std::string& b) {
  std::string how;
  for (const auto& x : d.effects)
    if ((x.name == a || x.name == b) && !x.separated_by.empty())
      how += fmt::format("{}{}: {}", how.empty() ? "" : "; ", x.name, x.separated_by);
  return how.empty() ? "a second loading rate, an unloading cycle or fragment sizes" : how;
}

std::string header_markdown(const SetDiagnosisReport& r) {
  const SetDiagnosisResult& d = r.result;
  const DiagnosisStepRecord& first = d.steps.front();
  const Diagnosis& d0 = first.diagnosis;
  std::string md = fmt::format("# Diagnosis: {}\n\nmeasurements {}, model {}, {} packing seeds, base parameters {}.\n",
                               d.verdict, r.measurements.string(), r.scene.string(), r.seeds, join(d.keys));
  md += fmt::format("Residual chi^2 {:.1f} over {} components; after what the base parameters can absorb {:.1f} "
                    "(p = {:.3g} against chi^2({})); base NRMSE {:.1f} %. {}\n\n",
                    d0.chi_square, first.lin.base.values.size(), d0.chi_square_unabsorbed, d0.p_value,
                    first.lin.base.values.size() - d.keys.size(), 100 * first.lin.base_comparison.nrmse(),
                    scoring_text(r.scoring));
  if (r.score_reference == ScoreReference::Welch)
    md += " Each component is Student t on its Welch-Satterthwaite degrees of freedom (specimen and replicate "
          "scatter estimated, sensor noise known), read as the normal score of equal tail probability "
          "(--score-reference welch).\n";
  if (!d.scaled_sizes.empty())
    md += "Trial sizes from the base run (plausible_from rules, docs/explanation/diagnosis.md):\n\n```\n" +
          d.scaled_sizes + "```\n\n";
  for (const auto& e : d.effects)
    if (!e.identifiable_at(r.coverage))
      md += fmt::format("{} is scored and refit but not named on these data: {}.\n\n", e.name,
                        e.unidentifiable_reason(r.coverage));
  return md;
}

std::string partial_text(const SetDiagnosisResult& d) {
  std::string md;
  if (!d.path.empty()) {
    std::vector<std::string> names;
    for (const auto& st : d.path) names.push_back(st.effect);
    md += fmt::format(" The path below explains part of it ({}), and leaves p = {:.2g}.", join(names, " + "),
                      d.path.back().p_after);
  }
  for (const auto& s : d.steps)
    if (d.path.empty() && !s.decision.best_partial.empty())
      for (const auto& e : s.decision.effects)
        if (e.name == s.decision.best_partial)
          md += fmt::format(" The best refit, {}, explains {:.0f} % of the excess chi^2 over noise ({:.1f}) and "
                            "leaves p = {:.2g}{}: not enough to name it.",
                            e.name, 100 * e.share_explained, s.decision.excess, e.p_after,
                            e.nrmse_rose ? " and raises the NRMSE" : "");
  return md;
}

std::string unidentifiable_text(const SetDiagnosisReport& r) {
  std::string md;
  for (const auto& s : r.result.steps) {
    if (s.decision.unidentifiable.empty()) continue;
    const CandidateEffect* e = r.result.effect(s.decision.unidentifiable);
    double p_after = 0;
    for (const auto& c : s.decision.effects)
      if (c.name == e->name) p_after = c.p_after;
    md += fmt::format(" {}'s refit would leave noise (p after {:.2g}), but {}{}.", e->name, p_after,
                      e->unidentifiable_reason(r.coverage),
                      e->separated_by.empty() ? "" : fmt::format(" ({})", e->separated_by));
  }
  return md;
}

std::string unexplained_markdown(const SetDiagnosisReport& r) {
  const SetDiagnosisResult& d = r.result;
  std::string md;
  if (d.base_out_of_range)
    md += "No candidate explains the structured residual, but the base model is out of range, not complete: the "
          "base refit reached its bound (below), so the base parameters cannot absorb what they should, and no "
          "conclusion about missing physics follows. Recalibrate the base parameters first (`shard calibrate`, "
          "or --set the parameter nearer the bound's value) and diagnose again.";
  else
    md += fmt::format("No candidate explains the structured residual: the missing physics is not in the library "
                      "({}), or more than --max-effects {} effects are at work.",
                      r.library.string(), r.max_effects);
  md += partial_text(d) + unidentifiable_text(r);
  if (d.resized_p)
    md += fmt::format(" Re-sized around itself (the next step's base refit), {} leaves p = {:.2g}: the base model "
                      "with {} might be adequate once calibrated (`shard calibrate --with {}` tests it), but its "
                      "own refit did not reach noise, so it is not named.",
                      d.path.back().effect, *d.resized_p, d.path.back().effect, d.path.back().effect);
  // Say what the data show that the base model does not, in the comparison's words, and how a
  // user adds the missing physics: the library is open.
  md += "\n\nWhat the base model misses:";
  const RateComparison& bc = d.steps.front().lin.base_comparison;
  for (std::size_t k = 0; k < bc.at.size(); ++k)
    md += fmt::format(" {}{}", bc.at.size() > 1 ? fmt::format("at {:g} m/s: ", bc.rates[k]) : "", bc.at[k].verdict);
  md += " To add an effect: `shard new-plugin` writes a one-file plugin whose new parameter has a neutral value "
        "(docs/how-to/write-a-plugin.md); an [[effect]] entry for it in the library lets diagnose try it and `shard "
        "calibrate --with` fit it.";
  return md + "\n\n";
}

std::string verdict_markdown(const SetDiagnosisReport& r) {
  const SetDiagnosisResult& d = r.result;
  const DiagnosisStepRecord& first = d.steps.front();
  const Diagnosis& d0 = first.diagnosis;
  if (d.verdict == kAdequate && first.refits.empty())
    return "The residual left after the base parameters is compatible with noise: no effect is needed.\n\n";
  if (d.verdict == kAdequate)
    return fmt::format("The base parameters refitted (simulated, not predicted) leave chi^2 {:.1f} over {} degrees of "
                       "freedom, p = {:.2g}: compatible with noise, so no effect is needed. The score test's lead "
                       "({}, p = {:.2g}) was not borne out by the refits below; an effect too weak for these data "
                       "cannot be told from noise (more specimens or another rate would).\n\n",
                       first.refits[0].chi_square, first.lin.base.values.size() - d.keys.size(),
                       first.decision.base_p, d0.ranking.empty() ? "-" : d0.ranking.front().name,
                       d0.ranking.empty() ? 1.0 : d0.ranking.front().p_value);
  if (d.verdict == kUnexplained) return unexplained_markdown(r);
  if (d.path.size() > 1)
    return fmt::format("{} effects, added one after the other; each step's refit is simulated (table below).\n\n",
                       d.path.size());
  return "";
}

std::string path_markdown(const SetDiagnosisResult& d) {
  if (d.path.empty()) return "";
  std::string md = "| step | effect added | value | chi^2 before -> after | NRMSE before -> after | p after | |\n"
                   "|---|---|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < d.path.size(); ++k) {
    const auto& st = d.path[k];
    const CandidateEffect* e = d.effect(st.effect);
    md += fmt::format("| {} | {} | {} | {:.1f} -> {:.1f} | {:.1f} -> {:.1f} % | {:.2g} | {} |\n", k + 1, st.effect,
                      e ? e->sized(st.value) : fmt::format("{:.4g}", st.value), st.chi_square_before, st.chi_square_after, 100 * st.nrmse_before,
                      100 * st.nrmse_after, st.p_after,
                      st.named ? "named: what remains is noise" : "kept: explains most of the excess, structure remains");
  }
  md += fmt::format("\nThe path's model, every size refit at its last step: {}.{}\n\n", values_text(d.keys, d.model),
                    d.path.size() > 1 ? " Sizes of effects found together are correlated (each step re-sizes the earlier "
                                        "ones)."
                                      : "");
  return md;
}

std::string ranking_markdown(const SetDiagnosisResult& d, const Diagnosis& diagnosis) {
  std::string md =
      "| effect | score (LM) | p-value | seeds' p | explains | absorbed by base | estimated value | dAIC | dBIC | regimes/features it explains |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : diagnosis.ranking) {
    const CandidateEffect* e = d.effect(r.name);
    md += fmt::format("| {}{} | {:.2f} | {:.3g} | {}{} | {:.0f} % | {:.0f} % | {}{} | {:+.1f} | {:+.1f} | {} |\n", r.name,
                      r.identifiable ? "" : " (not nameable on these data: above)",
                      r.score, r.p_value, r.seed_p == 0 ? "-" : fmt::format("{:.2g}", r.seed_p),
                      r.resolved ? "" : " (not resolved by the seeds)", 100 * r.explained, 100 * r.absorbed,
                      e->sized(e->neutral + r.size),
                      !r.at_bound ? "" : r.size == 0 ? " (the data ask for it reversed: outside its physical range)"
                                                     : " (clamped at its physical bound)",
                      r.delta_aic, r.delta_bic, join(r.explains));
  }
  return md;
}

std::string refit_row(const SetDiagnosisResult& d, const DiagnosisStepRecord& s, std::size_t c) {
  const RefitRun& cf = s.refits[c];
  const ConfirmedEffect* ce = s.confirmed(c);
  const std::string v = values_text(d.keys, cf.plan.model);
  if (!cf.failure.empty()) return fmt::format("| {} | run failed | - | - | - | - | - | - | - | {} |\n", cf.name, v);
  return fmt::format("| {}{}{} | {:.1f} | {:.1f} %{} | {} | {:+.1f} | {:+.1f} | {} | {} | {} | {} |\n", cf.name,
                     ce && !ce->identifiable ? " (not nameable at these rates)" : "",
                     cf.secant_steps > 0 ? fmt::format(" (secant {})", cf.secant_steps) : "", cf.chi_square,
                     100 * cf.nrmse,
                     ce && ce->nrmse_rose                      ? " (rose)"
                     : c == 0 && std::isfinite(cf.noise_nrmse) ? fmt::format(" (noise {:.1f} %)", 100 * cf.noise_nrmse)
                                                               : "",
                     std::isfinite(cf.failure_chi_square) ? fmt::format("{:.1f}", cf.failure_chi_square) : "-",
                     cf.delta_aic, cf.delta_bic, ce ? fmt::format("{:.0f} %", 100 * ce->share_explained) : "-",
                     ce ? fmt::format("{:.2g}", ce->p_after) : fmt::format("{:.2g}", s.decision.base_p),
                     ce ? fmt::format("{:.2g}", ce->p_drop) : "-", v);
}

std::string kept_markdown(const SetDiagnosisResult& d, const DiagnosisStepRecord& s) {
  const RefitRun& kc = *s.kept_converged;
  if (kc.secant_steps == 0)
    return fmt::format("\nKept: {}; no secant step lowered its refit's chi^2, so that refit is the next step's model.\n",
                       kc.name);
  const RefitRun* linear = &kc;
  for (const auto& c : s.refits)
    if (c.name == kc.name) linear = &c;
  return fmt::format("\nKept: {}, carried towards its minimum before the next step by {} secant step{} (until a step "
                     "gains less than {:g} in chi^2, at most --refit-iterations): {:.4g} -> {}, chi^2 {:.2f} -> "
                     "{:.2f}, NRMSE {:.1f} -> {:.1f} %; {}.\n",
                     kc.name, kc.secant_steps, kc.secant_steps == 1 ? "" : "s", kConvergedChiSquare,
                     linear->effect_value, kc.effect ? kc.effect->sized(kc.effect_value) : fmt::format("{:.4g}", kc.effect_value), linear->chi_square,
                     kc.chi_square, 100 * linear->nrmse, 100 * kc.nrmse, values_text(d.keys, kc.plan.model));
}

std::string refits_markdown(const SetDiagnosisResult& d, const DiagnosisStepRecord& s) {
  if (s.refits.empty()) return "";
  std::string md = fmt::format(
      "\nConfirmation runs (simulated, not predicted; excess chi^2 of the base refit over its {} degrees of freedom: "
      "{:.1f}; failure point: the failure displacement's squared score, not judged):\n\n| model | chi^2 | NRMSE | "
      "failure point | dAIC vs base refit | dBIC | share of excess | p after | p of the drop | values "
      "|\n|---|---|---|---|---|---|---|---|---|---|\n",
      s.lin.base.values.size() - s.lin.jacobian.size(), s.decision.excess);
  for (std::size_t c = 0; c < s.refits.size(); ++c) md += refit_row(d, s, c);
  for (const auto& cf : s.refits) {
    if (!cf.failure.empty())
      md += fmt::format("\nThe refit with {} did not run to the end and is left out: {}\n", cf.name, cf.failure);
    if (!cf.plan.at_bound.empty())
      md += fmt::format("\nAt bound in the {} refit: {}.{}\n", cf.name, join(cf.plan.at_bound, "; "),
                        cf.plan.base_at_bound && cf.name == "base refit"
                            ? " The base cannot absorb this within the refit's range: the base model is out of "
                              "range for these data"
                            : "");
  }
  if (s.kept_converged) md += kept_markdown(d, s);
  for (const auto& e : s.decision.effects)
    if (!e.resolved && e.share_explained >= 0.5)
      md += fmt::format("\n{}'s refit lowered chi^2 on the mean of the packing seeds but not seed by seed (p = {:.2g} "
                        "that the seeds' scatter alone moves it so): its simulated change is no larger than the "
                        "model's own packing scatter, so it is neither named nor kept. More packing seeds "
                        "(--seeds) or a larger specimen resolve a small effect.\n",
                        e.name, e.seed_p);
  for (const auto& e : s.decision.effects)
    if (e.nrmse_rose && e.share_explained >= 0.5)
      md += fmt::format("\n{}'s refit lowered chi^2 but raised the NRMSE above the base refit's: not an improvement "
                        "of the curve, so it is neither named nor kept (the base refit's noise floor, the NRMSE noise "
                        "alone gives: {:.1f} %).\n",
                        e.name, 100 * s.refits.front().noise_nrmse);
  return md;
}

std::string separation_markdown(const SetDiagnosisResult& d, const DiagnosisStepRecord& s) {
  std::string md;
  for (const auto& rival : s.decision.rivals) {
    double rival_chi2 = 0, named_chi2 = 0;
    for (const auto& e : s.decision.effects) {
      if (e.name == rival) rival_chi2 = e.chi_square;
      if (e.name == s.decision.verdict) named_chi2 = e.chi_square;
    }
    md += fmt::format("\n{}'s refit (chi^2 {:.1f}) explains these data almost as well as {}'s ({:.1f}; within {:g}): "
                      "they cannot tell the two apart. Measurements that would: {}.\n",
                      rival, rival_chi2, s.decision.verdict, named_chi2, ConfirmationRule{}.rival_chi_square,
                      separating_text(d, rival, s.decision.verdict));
  }
  for (const auto& [a, b] : s.diagnosis.indistinguishable)
    md += fmt::format("\n{} and {} have nearly parallel signatures here: these data cannot tell them apart. "
                      "Measurements that would: {}.\n",
                      a, b, separating_text(d, a, b));
  for (const auto& r : s.diagnosis.ranking)
    if (r.absorbed > 0.9)
      md += fmt::format("\n{}: {:.0f} % of its signature is absorbed by the base parameters: a calibration of {} "
                        "alone would hide it.\n",
                        r.name, 100 * r.absorbed, join(d.keys));
  return md;
}

std::string step_markdown(const SetDiagnosisResult& d, std::size_t k) {
  const DiagnosisStepRecord& s = d.steps[k];
  std::string md;
  if (d.steps.size() > 1)
    md += fmt::format("## Step {}: {}\n\nAfter {} nuisance parameters: chi^2 {:.1f} (p = {:.3g}).\n\n", k + 1,
                      model_name(s.model), s.lin.jacobian.size(), s.diagnosis.chi_square_unabsorbed, s.diagnosis.p_value);
  return md + ranking_markdown(d, s.diagnosis) + refits_markdown(d, s) + separation_markdown(d, s) + "\n";
}

std::string health_markdown(const RunHealth& h) {
  std::string md = fmt::format(
      "Largest kinetic/elastic energy ratio before breakage (deformation, less the rigid-body motion): {:.2g} over the "
      "base and the refits; {:.2g} over the effects' trials at their library sizes (not judged: a probe, not a model "
      "of the data).\n",
      h.max_kinetic_to_elastic, h.max_probe_kinetic_to_elastic);
  if (!h.dynamic_warning.empty()) md += fmt::format("\n**Warning.** {}.\n", h.dynamic_warning);
  return md;
}

io::Json ranking_json(const SetDiagnosisResult& d, const Diagnosis& diagnosis) {
  io::Json out = io::Json::array();
  for (const auto& r : diagnosis.ranking)
    out.push_back({{"name", r.name}, {"score", r.score}, {"p_value", r.p_value}, {"explained", r.explained},
                   {"absorbed", r.absorbed}, {"value", d.effect(r.name)->neutral + r.size},
                   {"at_bound", r.at_bound}, {"identifiable", r.identifiable}, {"seed_p", r.seed_p},
                   {"resolved", r.resolved}});
  return out;
}

io::Json refit_json(const RefitRun& cf, const ConfirmedEffect* ce, const ConfirmationDecision& decision,
                    std::size_t step) {
  io::Json residual = io::Json::object();
  for (std::size_t i = 0; i < cf.residual.values.size(); ++i) residual[cf.residual.names[i]] = cf.residual.values[i];
  // A refit that failed has null numbers (JSON has no infinity) and its error.
  return {{"name", cf.name}, {"chi_square", cf.chi_square}, {"nrmse", cf.nrmse}, {"delta_aic", cf.delta_aic},
          {"delta_bic", cf.delta_bic}, {"share_explained", ce ? ce->share_explained : 0.0},
          {"p_after", ce ? ce->p_after : decision.base_p}, {"p_drop", ce ? ce->p_drop : 1.0}, {"value", cf.effect_value},
          {"failure", cf.failure}, {"step", step}, {"at_bound", join(cf.plan.at_bound, "; ")},
          {"nrmse_rose", ce && ce->nrmse_rose}, {"seed_p", ce ? ce->seed_p : 0.0},
          {"failure_point_chi_square", cf.failure_chi_square},
          {"secant_steps", cf.secant_steps}, {"residual", std::move(residual)}};
}

// Every step's refits, the first step's first.
io::Json refits_json(const std::vector<DiagnosisStepRecord>& steps) {
  io::Json out = io::Json::array();
  for (std::size_t k = 0; k < steps.size(); ++k)
    for (std::size_t c = 0; c < steps[k].refits.size(); ++c)
      out.push_back(refit_json(steps[k].refits[c], steps[k].confirmed(c), steps[k].decision, k + 1));
  return out;
}

io::Json path_json(const std::vector<DiagnosisStep>& path) {
  io::Json out = io::Json::array();
  for (const auto& st : path)
    out.push_back({{"effect", st.effect}, {"value", st.value}, {"chi_square_before", st.chi_square_before},
                   {"chi_square_after", st.chi_square_after}, {"nrmse_before", st.nrmse_before},
                   {"nrmse_after", st.nrmse_after}, {"p_after", st.p_after}, {"named", st.named}});
  return out;
}

}  // namespace

std::string set_diagnosis_markdown(const SetDiagnosisReport& r) {
  const SetDiagnosisResult& d = r.result;
  std::string md = header_markdown(r) + verdict_markdown(r) + path_markdown(d);
  for (std::size_t k = 0; k < d.steps.size(); ++k) md += step_markdown(d, k);
  return md + health_markdown(d.health);
}

io::Json set_diagnosis_json(const SetDiagnosisReport& r) {
  const SetDiagnosisResult& d = r.result;
  const DiagnosisStepRecord& first = d.steps.front();
  io::Json json = io::json_document(kDiagnoseFormatVersion);
  json["verdict"] = d.verdict;
  json["chi_square"] = first.diagnosis.chi_square;
  json["chi_square_unabsorbed"] = first.diagnosis.chi_square_unabsorbed;
  json["p_value"] = first.diagnosis.p_value;
  json["nrmse"] = first.lin.base_comparison.nrmse();
  json["ranking"] = ranking_json(d, first.diagnosis);
  json["confirmations"] = refits_json(d.steps);
  json["unidentifiable"] = d.unidentifiable;
  json["excess"] = first.decision.excess;
  json["partial"] = first.decision.best_partial;
  json["rivals"] = d.steps.back().decision.rivals;
  json["path"] = path_json(d.path);
  json["base_out_of_range"] = d.base_out_of_range;
  json["model"] = d.path.empty() ? std::string() : values_text(d.keys, d.model);
  json["resized_p"] = d.resized_p ? io::Json(*d.resized_p) : io::Json();
  json["dynamic_warning"] = d.health.dynamic_warning;
  return json;
}

}  // namespace shard
