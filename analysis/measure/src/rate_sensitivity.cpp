// The set's rate dependence of its strength (shard/measure/rate_sensitivity.hpp) and the naming
// rule that asks for it (require_resolved_rate_dependence).
#include "shard/measure/rate_sensitivity.hpp"

#include <algorithm>
#include <cmath>

#include "paired_seeds.hpp"
#include "shard/measure/contrast_diagnosis.hpp"
#include "shard/measure/contrast_study.hpp"
#include "shard/measure/rate_groups.hpp"
#include "shard/measure/statistics.hpp"

namespace shard::measure {

namespace {

constexpr double kIntervalLevel = 0.95;

std::size_t peak_force_component() {
  const auto& names = contrast_component_names();
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), "ln_peak_force") - names.begin());
}

// A group's sample variance of the mean of one component, with its degrees of freedom.
VarianceTerm mean_variance(const std::vector<std::vector<double>>& rows, std::size_t component) {
  std::vector<double> x;
  for (const auto& r : rows) x.push_back(r[component]);
  const double sd = sample_sd(x);
  return {sd * sd / static_cast<double>(x.size()), static_cast<double>(x.size()) - 1};
}

}  // namespace

std::size_t RateSensitivity::specimens_needed() const {
  if (!(subcritical > 0)) return specimens_per_rate;
  const double ratio = half_width / subcritical;
  return static_cast<std::size_t>(std::ceil(static_cast<double>(specimens_per_rate) * ratio * ratio));
}

std::optional<RateSensitivity> ContrastStudy::rate_sensitivity(const Contrast& c, const Simulated& base,
                                                               double exponent) const {
  std::size_t slow = 0, fast = 0;  // positions in c.groups
  for (std::size_t k = 1; k < c.groups.size(); ++k) {
    if (groups_[c.groups[k]].rate < groups_[c.groups[slow]].rate) slow = k;
    if (groups_[c.groups[k]].rate > groups_[c.groups[fast]].rate) fast = k;
  }
  const ContrastGroup& gs = groups_[c.groups[slow]];
  const ContrastGroup& gf = groups_[c.groups[fast]];
  if (same_rate(gs.rate, gf.rate)) return std::nullopt;
  const std::size_t m = contrast_component_names().size(), f = peak_force_component();
  RateSensitivity r;
  r.slow_rate = gs.rate, r.fast_rate = gf.rate;
  r.exponent = exponent;
  r.specimens_per_rate = std::min(gs.components.size(), gf.components.size());
  r.strength_contrast = c.difference[slow * m + f];
  const auto covariance = spd_inverse(c.weight);
  r.u_strength_contrast = std::sqrt(covariance[slow * m + f][slow * m + f]);
  // Held against the same reference group, the reference cancels in the change; against two
  // (a reference tested at both rates) its own rate change is part of it.
  r.change = c.difference[fast * m + f] - c.difference[slow * m + f];
  std::vector<VarianceTerm> terms = {mean_variance(gs.components, f), mean_variance(gf.components, f)};
  if (!same_rate(gs.reference_rate, gf.reference_rate))
    for (const ContrastGroup& g : groups_)
      if (g.set == sets_.reference.value_or(sets_.sets.size()) &&
          (same_rate(g.rate, gs.reference_rate) || same_rate(g.rate, gf.reference_rate)))
        terms.push_back(mean_variance(g.components, f));
  // The base model's own change between the two rates, paired on its packing seeds.
  std::vector<double> shift, var_of_shift;
  paired(components(base, gf.rate), components(base, gs.rate), shift, var_of_shift);
  const std::size_t seeds = base.curves[rate_index(gf.rate)].size();
  terms.push_back({var_of_shift[f], static_cast<double>(seeds) - 1});
  double variance = 0;
  for (const auto& t : terms) variance += t.variance;
  r.u_change = std::sqrt(variance);
  r.dof = satterthwaite_dof(terms, 0);
  r.half_width = student_t_quantile(kIntervalLevel, r.dof) * r.u_change;
  r.subcritical = std::log(gf.rate / gs.rate) / (exponent + 1);
  return r;
}

std::vector<std::string> named_effects(const SetDiagnosis& d, const ContrastOptions& options) {
  const std::string& v = d.decision.verdict;
  if (v == kNoDifference || v == kUnexplainedDifference) return {};
  if (!names_a_pair(d, options)) return {v};
  return {d.pair->first, d.pair->second};
}

void require_resolved_rate_dependence(std::vector<SetDiagnosis>& sets, const ContrastStudy& study,
                                      const ContrastStudy::Simulated& base,
                                      const std::vector<CandidateEffect>& effects, const ContrastOptions& options) {
  for (auto& d : sets) {
    d.rate_sensitivity = study.rate_sensitivity(d.contrast, base, options.subcritical_exponent);
    const std::vector<std::string> names = named_effects(d, options);
    if (!d.rate_sensitivity || names.empty()) continue;
    const bool rate_independent = std::all_of(names.begin(), names.end(), [&](const std::string& n) {
      const CandidateEffect* e = find_effect(effects, n);
      return e && e->rates_needed <= 1;
    });
    const RateSensitivity& r = *d.rate_sensitivity;
    if (!rate_independent || !r.strength_differs() || (r.resolved() && !r.rate_dependent())) continue;
    d.withheld = d.decision.verdict;
    d.withheld_by = WithheldBy::rate;
    d.decision.verdict = kUnexplainedDifference;
    d.decision.rivals.clear();
  }
}

}  // namespace shard::measure
