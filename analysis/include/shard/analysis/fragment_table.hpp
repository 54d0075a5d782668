#pragma once
// One row per fragment: what a breakage test reports about each piece.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "shard/analysis/components.hpp"
#include "shard/types.hpp"

namespace shard::analysis {

// Per-particle inputs, all of the same length N (row order of one frame).
struct ParticleSample {
  std::span<const Index> id;        // stable particle id
  std::span<const Vec3> position;   // m
  std::span<const Vec3> velocity;   // m/s
  std::span<const double> radius;   // m
  std::span<const double> mass;     // kg
  std::span<const std::int32_t> body;  // parent body id; empty span means one parent (0)
  std::size_t size() const { return id.size(); }
};

// Throws std::invalid_argument naming the first array whose length differs from id's.
void check_sample(const ParticleSample& particles);

struct Fragment {
  Index label = 0;             // canonical: 0 is the heaviest
  std::size_t particles = 0;
  double mass = 0;             // kg
  double volume = 0;           // m^3, sum of sphere volumes (pores between spheres excluded)
  Vec3 centre = Vec3::Zero();  // m, centre of mass
  Vec3 velocity = Vec3::Zero();  // m/s, mass-weighted (momentum / mass)
  double d_eq = 0;             // m, diameter of the sphere of the fragment's volume
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();  // m, bounds of the spheres themselves
  std::int32_t body = 0;       // parent body carrying the largest share of the fragment's mass
  bool mixed_bodies = false;   // particles of more than one body (bonded across bodies)
  Index smallest_id = 0;       // smallest stable particle id, the tie-break of the numbering
};

double sphere_volume(double radius);
double equivalent_diameter(double volume);

// labels: canonical labels in [0, count) per particle. Returns count rows, row k = fragment k.
std::vector<Fragment> fragment_table(const ParticleSample& particles, std::span<const Index> labels,
                                     Index count);

// The whole pipeline for one frame: union-find labelling, canonical numbering, table.
struct FragmentAnalysis {
  std::vector<Index> labels;
  std::vector<Fragment> fragments;
};
FragmentAnalysis analyse_fragments(const ParticleSample& particles, const BondList& bonds);

}  // namespace shard::analysis
