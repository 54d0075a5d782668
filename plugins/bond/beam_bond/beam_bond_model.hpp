#pragma once
// The seed paper's beam bond (README.md, seed eq. 3-13) as a BondModel, with the effect
// policies of effects/bond_effects.hpp composed in when any is on. The law is beam_law.hpp, at the
// SIMD width in blocks (beam_batch.hpp) and at width 1 for the lanes a block leaves.
#include <cstddef>
#include <cstdint>

#include "beam_batch.hpp"
#include "beam_geometry.hpp"
#include "effects/bond_effects.hpp"
#include "shard/bond_model.hpp"
#include "shard/params.hpp"

namespace shard::beam {

struct BeamBondParams {
  double youngs_modulus = 12.8e6;   // E_b, Pa (Table I)
  double shear_modulus = 0;         // G_b, Pa; 0 = E_b / (2 (1 + nu_b))
  double poisson_ratio = 0.25;      // nu_b, 1
  double shear_coefficient = 0.9;   // a_s, 1 (Timoshenko coefficient of a circular section)
  double radius_ratio = 1;          // lambda, 1: r_b = lambda min(r1, r2)
  double damping = 0;               // d, N s/m (eq. 4)
  double rotational_damping = 1;    // factor on the eq. 6 coefficients, 1 = as printed, 0 = off
  double critical_stress = 0.24e6;  // sigma_v,crit, Pa (Table I)
  bool breakage = true;
  BondEffects effects;              // Weibull strength, softening, viscosity, compression asymmetry

  double effective_shear_modulus() const {
    return shear_modulus > 0 ? shear_modulus : youngs_modulus / (2 * (1 + poisson_ratio));
  }
  static BeamBondParams from(const ParamSet& p);
};

class BeamBond final : public BondModel {
 public:
  // `isa`: the block step's instruction set, the widest this CPU runs unless a test picks one.
  explicit BeamBond(const BeamBondParams& params, BlockIsa isa = widest_block_isa());

  std::size_t state_size() const override;
  void initialize(BondBatch& batch) const override;
  TimeStepLimit time_step_limit(const BondBatch& batch) const override;
  void compute(BondBatch& batch) const override;
  // Every lane of a block writes its outputs; a fallback lane is rewritten by the per-bond path.
  bool writes_every_output() const override { return true; }
  // The same results bond by bond, the law at width 1 for every bond (the reference the tests
  // compare the SIMD widths to).
  void compute_reference(BondBatch& batch) const;
  // True when the law runs its effects variant (BondEffects::any()).
  bool with_effects() const { return block_.effects; }
  // The strength the model gives the bond between particles of stable ids a and b.
  double strength_of(std::int64_t id_a, std::int64_t id_b) const;

  const BeamBondParams& params() const { return p_; }
  const BlockConstants& block_constants() const { return block_; }

 private:
  BlockConstants constants_for(double dt) const;  // with the Maxwell arm's factors over dt


  BeamBondParams p_;
  double shear_modulus_;  // G_b actually used
  double weibull_modulus_ = 0;    // m of the strength law in effect (BondEffects::weibull_modulus; 0: none)
  double weibull_scale_ = 0;      // s0 of the strength law (0 when m = 0)
  BlockConstants block_;          // the parameters as the law reads them
  BlockFunction block_step_;
};

}  // namespace shard::beam
