#include "shard/measure/rate_groups.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace shard::measure {

std::vector<Specimen> specimens_at_rate(const MeasurementSet& set, double rate) {
  std::vector<Specimen> out;
  const auto rates = set.loading_rates();
  if (rate <= 0 && rates.size() > 1)
    throw std::runtime_error(fmt::format("the measurements have {} loading rates; choose one with --rate", rates.size()));
  for (const auto& s : set.specimens)
    if (rate <= 0 || std::abs(s.loading_rate - rate) <= 1e-9 * rate) out.push_back(s);
  if (out.empty()) throw std::runtime_error(fmt::format("no specimen at loading rate {} m/s", rate));
  return out;
}

RateGroups rate_groups(const MeasurementSet& set, double rate) {
  RateGroups g;
  const std::vector<double> rates = rate > 0 ? std::vector<double>{rate} : set.loading_rates();
  for (double r : rates) {
    std::vector<Specimen> at;
    for (const auto& s : set.specimens)
      if (std::abs(s.loading_rate - r) <= 1e-9 * r) at.push_back(s);
    if (at.empty()) throw std::runtime_error(fmt::format("no specimen at loading rate {} m/s", r));
    g.rates.push_back(r);
    g.specimens.push_back(std::move(at));
  }
  return g;
}

}  // namespace shard::measure
