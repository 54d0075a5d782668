#pragma once
// The contact pass's first loop over a tile of listed pairs (Simulation::contact_chunk): which pairs
// may touch, compacted in pair order. The scalar rule per pair is contact_candidates_scalar.hpp;
// on a CPU with AVX-512 (F, BW, VL) and BMI2 the groups of 8 pairs run here in lanes
// (contact_candidates_avx512.cpp, compiled for that set with -ffp-contract=off): the same IEEE
// operations per pair, so the same candidates, and the same outputs, byte for byte.
#include <cstddef>
#include <cstdint>


namespace shard {

// One tile's view (indices are shard::Index, 32 bits; this header stays free of Eigen so that the
// AVX-512 object needs no other instruction-set flags). Outputs have room for the tile's pairs plus 8 (a group stores 8 slots).
struct CandidateTile {
  const std::int32_t* first;      // the list's arrays, indexed by pair
  const std::int32_t* second;     // < 0: a wall
  const double* position;  // 3 per particle
  const double* radius;
  std::uint8_t* touching;  // per pair: touched at the last pass; set to "is a candidate"
  double* history;         // per pair, `stride` doubles: zeroed for a pair that stopped touching
  std::size_t stride;
  // Per candidate, in pair order: the pair, its ends as listed, whether it touched before.
  std::size_t* pair;
  std::int32_t* i;
  std::int32_t* j;
  std::uint8_t* touched;
};

// True when this CPU runs the AVX-512 loop.
bool candidate_lanes_available();

// Pairs [k, k + 8 * groups) in groups of 8, appended at slot c of the tile's outputs; returns the new c.
std::size_t candidate_groups_avx512(const CandidateTile& t, std::size_t k, std::size_t groups, std::size_t c);

}  // namespace shard
