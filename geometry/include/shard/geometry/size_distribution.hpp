#pragma once
// Particle size distribution (PSD) of the sub-particles: number-based cumulative distribution of
// the diameter, either uniform between d_min and d_max or tabulated.
#include <filesystem>
#include <vector>

namespace shard::geometry {

class SizeDistribution {
 public:
  // Uniform in diameter on [d_min, d_max] (d_min == d_max: monodisperse).
  static SizeDistribution uniform(double d_min, double d_max);
  // CSV with two columns: diameter [m], cumulative number fraction [0..1], non-decreasing, first
  // fraction 0 and last 1 ('#' lines and a header are skipped). Linear between the rows.
  // Throws std::runtime_error naming the file and the bad row.
  static SizeDistribution from_table(const std::filesystem::path& file);

  double d_min() const { return diameter_.front(); }
  double d_max() const { return diameter_.back(); }
  // Inverse CDF: the diameter at cumulative fraction u in [0, 1).
  double diameter_at(double u) const;
  double cdf(double diameter) const;
  double mean_diameter() const;
  // Kolmogorov-Smirnov distance between the empirical CDF of `diameters` and this distribution.
  double ks_distance(std::vector<double> diameters) const;

 private:
  std::vector<double> diameter_;  // ascending
  std::vector<double> fraction_;  // cumulative, 0 ... 1
};

}  // namespace shard::geometry
