#pragma once
// Bonds of a packing and the figures that say whether it is a good parent body (docs/reference/generators.md):
// density, coordination, PSD fidelity, bond-orientation isotropy, holes.
#include <string>
#include <utility>
#include <vector>

#include "shard/geometry/advancing_front.hpp"
#include "shard/geometry/size_distribution.hpp"
#include "shard/types.hpp"

namespace shard::geometry {

using BondList = std::vector<std::pair<Index, Index>>;

// Bonds every pair whose surface gap |c_i - c_j| - r_i - r_j is below gap * (r_i + r_j) / 2,
// i.e. `gap` is relative to the pair's mean radius (dimensionless). Pairs come out sorted (i < j).
BondList bond_by_gap(const SpherePacking& packing, double gap);

// Number of connected components of the bond graph (isolated spheres count as components).
std::size_t bond_components(std::size_t particles, const BondList& bonds);

// Frobenius norm of the deviatoric part of F = sum(n n^T) / N_b over bond directions n:
// 0 for an isotropic bond network, sqrt(2/3) ~ 0.816 when all bonds are parallel.
double fabric_deviator(const SpherePacking& packing, const BondList& bonds);

// Largest overlap r_i + r_j - |c_i - c_j| divided by min(r_i, r_j) over all pairs (<= 0: none).
double max_relative_overlap(const SpherePacking& packing);

struct QualityInputs {
  double body_volume = 0.0;                   // [m^3]; 0: unknown (no solid fraction)
  const SizeDistribution* target = nullptr;   // null: no KS distance
  const SignedDistance* distance = nullptr;   // null: no hole fraction
  Box bounds{};                               // sampling box for the hole fraction
  std::size_t hole_samples = 100000;
  double seconds = -1.0;                      // < 0: not reported
};

// Fraction of the body volume (sampled on a regular lattice) further than d_max from every sphere.
double hole_fraction(const SpherePacking& packing, const SignedDistance& distance, const Box& bounds,
                     double d_max, std::size_t samples);

// particles, bonds, solid_fraction, coordination, psd_ks_distance, fabric_deviator, hole_fraction,
// bond_components, max_overlap, generation_seconds (those computable from the inputs).
std::vector<std::pair<std::string, double>> packing_quality(const SpherePacking& packing, const BondList& bonds,
                                                            const QualityInputs& inputs);

// "particles=41788 bonds=235220 ..." for the run log.
std::string format_quality(const std::vector<std::pair<std::string, double>>& quality);

}  // namespace shard::geometry
