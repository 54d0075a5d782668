#pragma once
// The contact pass's per-pair arithmetic of touching particle pairs (Simulation::contact_chunk):
// the geometry (normal, overlap, relative velocity at the contact point, relative spin, effective
// radius and mass) before the contact law, and the torques on both ends after it. The scalar rule
// per slot is contact_geometry_scalar.hpp; on a CPU with AVX-512 (F, BW, VL) the compacted slots
// run here 8 at a time (contact_geometry_avx512.cpp, compiled for that set with -ffp-contract=off):
// the same IEEE operations in the same order per slot, so the same bits. The geometry's square root
// and five divisions per pair go to the divider 8 pairs to an instruction instead of one by one.
#include <cstddef>
#include <cstdint>

namespace shard {

// A block's view (indices are shard::Index, 32 bits; this header stays free of Eigen so that the
// AVX-512 object needs no other instruction-set flags). Rows of 3 doubles per particle or slot.
struct PairGeometryTile {
  const double* position;  // the particles' arrays
  const double* velocity;
  const double* omega;
  const double* radius;
  const double* mass;
  const std::int32_t* i;  // per slot: the pair's ends; j < 0 is a wall
  const std::int32_t* j;
  double* normal;  // per slot, outputs
  double* velocity_rel;
  double* omega_rel;
  double* overlap;
  double* r_eff;
  double* m_eff;
};

// The torques of a block's particle pairs, from the contact law's force and couple per slot: on
// end a (arm_a x f) + couple, on end b (arm_b x (-f)) - couple, the arms s n from each centre with
// s_a = -(r_a - overlap / 2) and s_b = r_b - overlap / 2.
struct PairLoadsTile {
  const double* radius;  // the particles'
  const std::int32_t* i;  // per slot: the pair's ends; j < 0 is a wall
  const std::int32_t* j;
  const double* force;  // per slot, rows of 3: the law's outputs and the geometry
  const double* couple;
  const double* normal;
  const double* overlap;
  double* torque_a;  // per slot, rows of 3, outputs
  double* torque_b;
};

// True when this CPU runs the AVX-512 geometry and loads.
bool pair_geometry_lanes_available();

// Slots [0, 8 * groups) in groups of 8 as particle pairs. A wall slot (j < 0) is computed as the
// pair (i, i) and must be written again by the caller.
void pair_geometry_avx512(const PairGeometryTile& t, std::size_t groups);

// Slots [0, 8 * groups) in groups of 8 as particle pairs; a wall slot's values are meaningless.
void pair_loads_avx512(const PairLoadsTile& t, std::size_t groups);

}  // namespace shard
