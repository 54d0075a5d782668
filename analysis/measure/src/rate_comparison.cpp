#include "shard/measure/rate_comparison.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace shard::measure {

ResidualVector RateComparison::residual_vector() const {
  ResidualVector v;
  for (std::size_t k = 0; k < at.size(); ++k) {
    const ResidualVector r = at[k].residual_vector();
    for (std::size_t i = 0; i < r.values.size(); ++i) {
      v.names.push_back(at.size() > 1 ? fmt::format("{}@{:g}", r.names[i], rates[k]) : r.names[i]);
      v.values.push_back(r.values[i]);
    }
  }
  return v;
}

ResidualVector RateComparison::seed_residual_vector(std::size_t seed, const RateComparison& band) const {
  RateComparison one;
  one.rates = rates;
  for (std::size_t k = 0; k < seed_at.at(seed).size(); ++k) one.at.push_back(with_simulated_band(seed_at[seed][k], band.at.at(k)));
  return one.residual_vector();
}

std::vector<ResidualVector> RateComparison::seed_residual_vectors(const RateComparison& band) const {
  std::vector<ResidualVector> out;
  for (std::size_t seed = 0; seed < seed_at.size(); ++seed) out.push_back(seed_residual_vector(seed, band));
  return out;
}

double RateComparison::nrmse() const {
  double s = 0;
  for (const auto& c : at) s += c.nrmse * c.nrmse;
  return at.empty() ? 0 : std::sqrt(s / static_cast<double>(at.size()));
}

double RateComparison::noise_nrmse() const {
  double s = 0;
  for (const auto& c : at) s += c.noise_nrmse() * c.noise_nrmse();
  return at.empty() ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(s / static_cast<double>(at.size()));
}

double RateComparison::chi_square() const {
  double x = 0;
  for (double r : residual_vector().values) x += r * r;
  return x;
}

std::vector<RateComparison> simulate_and_compare(Simulator& simulator, const MeasuredRates& data,
                                                 const std::vector<ModelPlan>& models, std::ostream& log) {
  const RateGroups& groups = data.groups;
  if (!models.empty()) {
    std::vector<Specimen> every_rate;
    for (const auto& at : groups.specimens) every_rate.insert(every_rate.end(), at.begin(), at.end());
    simulator.check_inputs(models.front(), every_rate, data.metadata);
  }
  std::vector<ModelPlan> runs;
  for (const auto& m : models)
    for (double r : groups.rates) {
      ModelPlan at = m;
      at.loading_rate = r;
      runs.push_back(std::move(at));
    }
  const auto sims = simulator.simulate(runs, log);
  std::vector<RateComparison> out(models.size());
  for (std::size_t m = 0; m < models.size(); ++m) {
    out[m].rates = groups.rates;
    for (std::size_t k = 0; k < groups.rates.size(); ++k)
      out[m].at.push_back(compare(groups.specimens[k], data.metadata, sims[m * groups.rates.size() + k], data.compare));
    const std::size_t seeds = sims[m * groups.rates.size()].size();
    if (seeds > 1)
      for (std::size_t s = 0; s < seeds; ++s) {
        std::vector<Comparison> alone;
        for (std::size_t k = 0; k < groups.rates.size(); ++k)
          alone.push_back(compare(groups.specimens[k], data.metadata, {sims[m * groups.rates.size() + k].at(s)}, data.compare));
        out[m].seed_at.push_back(std::move(alone));
      }
  }
  return out;
}

}  // namespace shard::measure
