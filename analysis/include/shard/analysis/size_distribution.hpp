#pragma once
// Fragment size distribution (FSD): the mass-weighted cumulative distribution Q(d) of the
// fragments' equivalent sphere diameter d_eq, and its characteristic sizes x10, x50, x90.
//
// Q is built from the fragments sorted by d_eq (fragments of equal d_eq merged into one point):
//   d_1 < d_2 < ... < d_K,  Q_k = (mass of fragments with d_eq <= d_k) / total mass,  Q_K = 1.
// x_p (p in (0, 1]) interpolates d linearly in Q between consecutive points:
//   p <= Q_1:                 x_p = d_1 (no smaller fragment to interpolate from)
//   Q_{k-1} < p <= Q_k:       x_p = d_{k-1} + (p - Q_{k-1}) / (Q_k - Q_{k-1}) * (d_k - d_{k-1})
// so x_p is exact wherever p equals some Q_k, and a single fragment gives x10 = x50 = x90 = d_1.
#include <cstddef>
#include <span>
#include <vector>

#include "shard/analysis/fragment_table.hpp"

namespace shard::analysis {

struct DistributionPoint {
  double d = 0;          // m, equivalent diameter
  double cumulative = 0; // Q(d), mass fraction of fragments no larger than d
};

struct SizeDistribution {
  std::vector<DistributionPoint> points;  // ascending d
  std::size_t fragments = 0;
  double total_mass = 0;   // kg
  double x10 = 0, x50 = 0, x90 = 0;  // m
  double fines_size = 0;   // m, the size below which fragments count as fines (0: none)
  double fines_mass = 0;   // kg, mass of fragments with d_eq strictly below fines_size
  double fines_fraction() const { return total_mass > 0 ? fines_mass / total_mass : 0.0; }
};

// d and mass per fragment (same length, mass >= 0, total mass > 0 unless empty).
SizeDistribution size_distribution(std::span<const double> d, std::span<const double> mass,
                                   double fines_size = 0);
SizeDistribution size_distribution(const std::vector<Fragment>& fragments, double fines_size = 0);

// x_p of a distribution's points, p in (0, 1]; the rule above.
double characteristic_size(const std::vector<DistributionPoint>& points, double p);

}  // namespace shard::analysis
