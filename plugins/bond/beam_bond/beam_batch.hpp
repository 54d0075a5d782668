#pragma once
// beam_bond's step for a block of bonds at once: the law of beam_law.hpp at the SIMD width
// (xsimd::batch<double, A>, beam_block.hpp), compiled once per instruction set (AVX-512: 8 lanes,
// AVX2: 4, the x86-64-v2 baseline: 2) and chosen at run time. A lane the law leaves (the rare
// cases of beam_law.hpp) is flagged `fallback` and the caller evaluates its bond with the same law
// at width 1, which gives the same bits as the lanes would have.
#include <cstddef>
#include <cstdint>

#include "beam_law.hpp"
#include "shard/types.hpp"

namespace shard::beam {

inline constexpr std::size_t kBlockLanes = 64;  // at most 64: BlockOutput::fallback is one bit a lane

using BlockConstants = LawConstants;

// A block's inputs: its bonds' ends as the batch lists them (the block step orders each bond's
// ends itself: first = the smaller stable id, or the smaller index without ids), their state
// (kStateSize doubles each) and the particle fields as flat arrays (Vec3: x, y, z; Quat: x, y, z,
// w, Eigen's storage order).
struct BlockInput {
  const Index* i = nullptr;
  const Index* j = nullptr;
  const Index* id = nullptr;  // stable ids; null: the indices order the ends
  const double* state = nullptr;  // kStateSize doubles per bond; kEffectsStateSize, kViscousStateSize with effects
  const double* position = nullptr;
  const double* velocity = nullptr;  // read only with a viscous force
  const double* orientation = nullptr;
  const double* omega = nullptr;
  const double* radius = nullptr;
  const double* inertia = nullptr;
};

// Where the lanes write: the block's slots of the batch outputs (Vec3 as x, y, z), in the batch's
// orientation (force and torque_i on batch.i). Fallback lanes are written too, with meaningless
// values, for the caller to overwrite through the per-bond path.
struct BlockOutput {
  double* force = nullptr;
  double* torque_i = nullptr;
  double* torque_j = nullptr;
  double* energy = nullptr;
  std::uint64_t fallback = 0;  // bit l set: lane l not evaluated, run the per-bond path
  // With the arm: the block's state (the input's), where each evaluated lane stores its new
  // (Gamma, kappa) and arm strains (h_Gamma, h_kappa); a fallback lane's are left for its own step.
  double* state = nullptr;
};

// The block step evaluates lanes [0, n), n <= kBlockLanes. It is compiled for each instruction
// set (8 lanes of AVX-512, 4 of AVX2, 2 of the x86-64-v2 baseline); all round identically, and the
// tests check every one the CPU can run.
enum class BlockIsa { Baseline, Avx2, Avx512 };
using BlockFunction = void (*)(const BlockInput&, BlockOutput&, std::size_t, const BlockConstants&);
const char* name_of(BlockIsa isa);
bool runs_here(BlockIsa isa);
BlockFunction block_function(BlockIsa isa);  // precondition: runs_here(isa)
BlockIsa widest_block_isa();

}  // namespace shard::beam
