#pragma once
// The seed's filling algorithm (sec. III; docs/reference/generators.md): three mutually touching spheres as a
// seed, then an advancing front. Each next sphere, its radius drawn from the PSD, is placed tangent
// to three already placed spheres as close as possible to the seed, and accepted only if it
// overlaps no sphere and lies inside the body (signed distance <= -r).
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "shard/geometry/size_distribution.hpp"
#include "shard/geometry/stl.hpp"
#include "shard/types.hpp"

namespace shard::geometry {

// Signed distance to the body surface [m]: negative inside.
using SignedDistance = std::function<double(const Vec3&)>;

struct SpherePacking {
  std::vector<Vec3> centre;
  std::vector<double> radius;
};

struct FrontFillOptions {
  std::uint64_t seed = 0;
  // Two spheres overlap when their centre distance is below r_i + r_j - tol * min(r_i, r_j);
  // tangent placements are exact to ~1e-15 relative, so this only absorbs rounding.
  double overlap_tolerance = 1e-9;
  // Spacing of the probe lattice that finds the seed position, as a fraction of d_max.
  double probe_spacing = 0.5;
  // Also try spots tangent to two placed spheres and to the body's surface (its local tangent
  // plane). A plane face then ends in a layer of spheres that all touch it (each may cross it by
  // 1e-3 of its radius, the voxelized distance's rounding), instead of the grain-rough face a
  // front of tangent spheres leaves: a fixture bearing on the face meets that layer, not the one
  // grain that stands out furthest.
  bool conform_to_surface = false;
  // Step of the central differences that give the surface normal [m]; 0: d_min / 8.
  double normal_step = 0.0;
};

// Raised when the body cannot hold the seed (thinner than about d_max everywhere).
class FillError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Fills the body described by `distance` within `bounds`. The seed sits at the deepest probe point
// (ties: the one nearest the box centre). Front order: the front sphere nearest the seed point is
// worked on until nothing fits around it; around it, the candidate nearest the seed point wins.
// This grows the packing as a compact ball from the seed and leaves no distant islands.
// A sphere that cannot be placed keeps its radius for the next attempt, so the placed PSD follows
// the target except where large spheres no longer fit.
SpherePacking advancing_front_fill(const SignedDistance& distance, const Box& bounds,
                                   const SizeDistribution& psd, const FrontFillOptions& options);

}  // namespace shard::geometry
