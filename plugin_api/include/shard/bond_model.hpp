#pragma once
// Bond models (plugins/bond/*/README.md): massless beams between two particles. One batch call per step
// over all intact bonds; per-bond state (the bonded reference configuration and anything else a
// model needs) lives in a kernel array the model sizes, so checkpoints carry it.
#include <cstddef>
#include <cstdint>

#include "shard/params.hpp"
#include "shard/particles.hpp"
#include "shard/time_step.hpp"
#include "shard/types.hpp"

namespace shard {

enum class BondFailureMode : std::uint8_t { None = 0, Tension = 1, Bending = 2, Shear = 3, Torsion = 4 };

// Stresses of a bond at the moment it failed, in Pa.
struct BondStress {
  double sigma_axial = 0;  // tensile part of the normal stress (axial + bending)
  double tau = 0;          // shear + torsion
  double sigma_vm = 0;     // von Mises equivalent
  double tension = 0, bending = 0, shear = 0, torsion = 0;  // the four contributions
  BondFailureMode dominant = BondFailureMode::None;
};

struct BondBatch {
  std::size_t count = 0;
  double time = 0;  // s
  double dt = 0;    // s
  const Index* i = nullptr;
  const Index* j = nullptr;
  ParticleView particles;
  double* state = nullptr;  // state_size() doubles per bond
  // Outputs: force on i (j gets the opposite), torques on i and on j, elastic energy, zeroed by
  // the kernel unless the model writes every one of them (BondModel::writes_every_output);
  // broken[k] (always zeroed by the kernel) = 1 and stress[k] filled when bond k fails this step.
  Vec3* force = nullptr;
  Vec3* torque_i = nullptr;
  Vec3* torque_j = nullptr;
  double* energy = nullptr;
  std::uint8_t* broken = nullptr;
  BondStress* stress = nullptr;
};

class BondModel {
 public:
  virtual ~BondModel() = default;
  virtual std::size_t state_size() const = 0;
  // Records the bonded reference configuration of bonds [0, count) of `batch` (outputs unused).
  virtual void initialize(BondBatch& batch) const = 0;
  // Stiffest bond against lightest particle, over the bonds in `batch`.
  virtual TimeStepLimit time_step_limit(const BondBatch& batch) const = 0;
  virtual void compute(BondBatch& batch) const = 0;
  // True when compute() writes force, torque_i, torque_j and energy of every bond of the batch
  // (zeros for a broken one), so the kernel need not zero them first: ~8-10 % of a beam_bond
  // step (docs/explanation/performance.md).
  virtual bool writes_every_output() const { return false; }
};

}  // namespace shard
