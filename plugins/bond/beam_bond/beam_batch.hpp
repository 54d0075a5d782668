#pragma once
// beam_bond's step for a block of bonds at once, one bond per SIMD lane in a loop the compiler
// vectorises (docs/performance.md, session 3). It is the arithmetic of beam_geometry.hpp and
// beam_stress.hpp written out per scalar in exactly the order Eigen evaluates it there (including
// Eigen's SSE quaternion product and its halved sum for the last row of a 3x3 product), so every
// lane it accepts is bit-identical to the per-bond
// path. The effects variant (effects/bond_effects.hpp) composes the four effect policies into the
// same loop, bit-identical to the per-bond path with effects (tests/bond/test_beam_block.cpp).
//
// Only the common case is evaluated here: q_rel within 1e-9 of unit length, a relative rotation
// inside the arcsin series range, (with breakage) a bond the von Mises bound says cannot break and
// (with effects) an undamaged bond.
// Every other lane is flagged `fallback` and the caller runs the per-bond path on it.
#include <cstddef>
#include <cstdint>

#include "shard/types.hpp"

namespace shard::beam {

inline constexpr std::size_t kBlockLanes = 64;

// Per-batch constants (the same values the per-bond path uses).
struct BlockConstants {
  double youngs = 0, shear = 0, shear_coefficient = 0, radius_ratio = 0, damping = 0, strength = 0;
  double bend_scale = 0, twist_over_bend = 0;  // RotationalDamping's factors
  bool breakage = true;
  bool viscous_force = false;  // damping != 0: v12 is needed
  // The effects variant (per-bond strength and damage in the state, the Maxwell arm, the
  // compressive axial modulus); the arm's factors depend on the step and are set per batch.
  bool effects = false;
  bool arm = false;                // effects with the Maxwell arm (viscosity_time > 0)
  double compression_modulus = 0;  // r E_b
  double arm_decay = 1, arm_gain = 0;  // MaxwellArm over this batch's step
  double arm_modulus_ratio = 1;        // beta: the arm spring's energy is E_b h^2 / (2 beta)
};

// A block's inputs: its bonds' ends in the bond's own order (first = smaller stable id), their
// state (kStateSize doubles each) and the particle fields as flat arrays (Vec3: x, y, z;
// Quat: x, y, z, w, Eigen's storage order).
struct BlockInput {
  const Index* first = nullptr;
  const Index* second = nullptr;
  const std::int64_t* swapped = nullptr;  // 1: the batch lists the bond from its second end
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
  std::int64_t fallback[kBlockLanes];  // 1: lane not evaluated, run the per-bond path
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
