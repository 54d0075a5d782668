#include "shard/geometry/size_distribution.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "shard/io/csv.hpp"

namespace shard::geometry {

SizeDistribution SizeDistribution::uniform(double d_min, double d_max) {
  if (!(d_min > 0.0) || !(d_max >= d_min))
    throw std::invalid_argument(fmt::format("particle size distribution: need 0 < diameter_min <= "
                                            "diameter_max, got {} and {}",
                                            d_min, d_max));
  SizeDistribution psd;
  psd.diameter_ = {d_min, d_max};
  psd.fraction_ = {0.0, 1.0};
  return psd;
}

// Read by the one CSV reader (shard/io/csv.hpp): an optional header, ',' or ';' or tab, decimal
// commas, a units row ("mm;-" converts the diameters to m).
SizeDistribution SizeDistribution::from_table(const std::filesystem::path& file) {
  const auto t = io::CsvTable::read(file, io::CsvHeader::optional);
  SizeDistribution psd;
  for (const auto& row : t.rows()) {
    if (row.fields.size() < 2)
      t.fail(row, 0, "PSD table: one field", "write two columns, diameter_m and cumulative_fraction");
    const double d = t.number(row, 0, "diameter in m"), f = t.number(row, 1, "cumulative fraction");
    if (!(d > 0.0) || f < 0.0 || f > 1.0 ||
        (!psd.diameter_.empty() && (d <= psd.diameter_.back() || f < psd.fraction_.back())))
      t.fail(row, 0, "PSD table: diameters must be > 0 and increasing, fractions non-decreasing within [0, 1]",
             "sort the rows by diameter and give cumulative fractions from 0 to 1");
    psd.diameter_.push_back(d);
    psd.fraction_.push_back(f);
  }
  if (psd.diameter_.size() < 2 || psd.fraction_.front() != 0.0 || psd.fraction_.back() != 1.0)
    throw std::runtime_error(fmt::format("PSD table '{}': needs at least two rows, the first with cumulative "
                                         "fraction 0 and the last with 1",
                                         file.string()));
  return psd;
}

double SizeDistribution::diameter_at(double u) const {
  const auto it = std::upper_bound(fraction_.begin(), fraction_.end(), u);
  if (it == fraction_.begin()) return diameter_.front();
  if (it == fraction_.end()) return diameter_.back();
  const auto i = static_cast<std::size_t>(it - fraction_.begin());
  const double t = (u - fraction_[i - 1]) / (fraction_[i] - fraction_[i - 1]);
  return diameter_[i - 1] + t * (diameter_[i] - diameter_[i - 1]);
}

double SizeDistribution::cdf(double diameter) const {
  if (diameter <= diameter_.front()) return diameter == diameter_.back() ? 1.0 : 0.0;
  if (diameter >= diameter_.back()) return 1.0;
  const auto it = std::upper_bound(diameter_.begin(), diameter_.end(), diameter);
  const auto i = static_cast<std::size_t>(it - diameter_.begin());
  const double t = (diameter - diameter_[i - 1]) / (diameter_[i] - diameter_[i - 1]);
  return fraction_[i - 1] + t * (fraction_[i] - fraction_[i - 1]);
}

double SizeDistribution::mean_diameter() const {
  double mean = 0.0;
  for (std::size_t i = 1; i < diameter_.size(); ++i)
    mean += (fraction_[i] - fraction_[i - 1]) * 0.5 * (diameter_[i] + diameter_[i - 1]);
  return mean;
}

double SizeDistribution::ks_distance(std::vector<double> diameters) const {
  if (diameters.empty()) return 1.0;
  if (d_min() == d_max()) {  // a step CDF: the share of samples off the one diameter
    const auto off = std::count_if(diameters.begin(), diameters.end(),
                                   [&](double d) { return std::abs(d - d_min()) > 1e-12 * d_min(); });
    return static_cast<double>(off) / static_cast<double>(diameters.size());
  }
  std::sort(diameters.begin(), diameters.end());
  const double n = static_cast<double>(diameters.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < diameters.size(); ++i) {
    const double target = cdf(diameters[i]);
    // The empirical CDF jumps from i/n to (i+1)/n at this sample.
    worst = std::max({worst, std::abs(target - static_cast<double>(i) / n),
                      std::abs(static_cast<double>(i + 1) / n - target)});
  }
  return worst;
}

}  // namespace shard::geometry
