#pragma once
// beam_bond with four effects a measurement may show missing (docs/effects.md). Each has a
// neutral value at which this model runs exactly the arithmetic of beam_bond:
//   strength_weibull_modulus m      0  per-bond strength scatter (weibull_strength.hpp)
//   softening_ratio s               0  linear cohesive softening after the peak (cohesive_softening.hpp)
//   viscosity_time tau_v [s]        0  standard linear solid: a Maxwell arm of viscosity E_b tau_v
//   viscous_modulus_ratio beta      1  the arm's modulus over E_b (beta -> infinity: Kelvin-Voigt)
//   compression_stiffness_ratio     1  axial stiffness in compression, times E_b A_b / l0
#include <cstddef>
#include <cstdint>

#include "beam_bond_model.hpp"
#include "shard/bond_model.hpp"
#include "shard/params.hpp"

namespace shard::beam_plus {

struct BeamBondPlusParams {
  beam::BeamBondParams base;              // the beam_bond parameters, same names and defaults
  double strength_weibull_modulus = 0;    // m, 1; 0 = every bond has critical_stress
  std::uint64_t strength_seed = 0;        // seed of the per-bond strength hash
  double softening_ratio = 0;             // s, 1; fracture energy over peak elastic energy
  double viscosity_time = 0;              // tau_v, s; eta = E_b tau_v
  double viscous_modulus_ratio = 1;       // beta, 1; Maxwell arm modulus beta E_b, relaxation tau_v / beta
  double compression_stiffness_ratio = 1; // 1

  static BeamBondPlusParams from(const ParamSet& p);
};

// Per-bond state: beam_bond's 9 doubles, then the bond's strength and its damage; with viscosity
// on, the previous step's (Gamma, kappa) and the Maxwell arm's strains (h_Gamma, h_kappa).
inline constexpr std::size_t kStrengthSlot = 9;
inline constexpr std::size_t kDamageSlot = 10;
inline constexpr std::size_t kStateSize = 11;
inline constexpr std::size_t kPreviousStrainSlot = kStateSize;         // Gamma (3), then kappa (3)
inline constexpr std::size_t kArmStrainSlot = kPreviousStrainSlot + 6;  // h_Gamma (3), then h_kappa (3)
inline constexpr std::size_t kViscousStateSize = kArmStrainSlot + 6;

class BeamBondPlus final : public BondModel {
 public:
  explicit BeamBondPlus(const BeamBondPlusParams& params);

  std::size_t state_size() const override { return viscous() ? kViscousStateSize : kStateSize; }
  void initialize(BondBatch& batch) const override;
  TimeStepLimit time_step_limit(const BondBatch& batch) const override;
  void compute(BondBatch& batch) const override;
  bool writes_every_output() const override { return true; }  // intact bonds in full, broken ones zeroed

  const BeamBondPlusParams& params() const { return p_; }
  bool viscous() const { return p_.viscosity_time > 0; }
  // The strength this model gives the bond between particles of stable ids a and b.
  double strength_of(std::int64_t id_a, std::int64_t id_b) const;

 private:
  BeamBondPlusParams p_;
  double shear_modulus_;        // G_b actually used
  double compression_modulus_;  // ratio E_b: the axial modulus when Gamma_x < 0
  double weibull_scale_;        // s0 of the strength law (0 when m = 0)
};

}  // namespace shard::beam_plus
