#pragma once
// The physical effects composed into beam_bond's law (docs/reference/effects.md), each a policy with a name,
// its parameters and ONE neutral value per parameter, declared in its schema here and nowhere else:
//   weibull_strength       strength_cv [1] (neutral 0) or strength_weibull_modulus m [1] (neutral 0), strength_seed
//   softening              softening_ratio s [1] (neutral 0)
//   viscosity              viscosity_time tau_v [s] (neutral 0), viscous_modulus_ratio beta [1]
//   compression_asymmetry  compression_stiffness_ratio r [1] (neutral 1)
// A policy joins the law when `effects` names it or any of its parameters is away from its neutral
// value; each is exact at its neutral value, so naming it without moving its parameter reproduces
// plain beam_bond bit for bit. Any effect on switches the law to its effects variant, which
// composes all four at lane speed (beam_batch.hpp); the per-bond state then grows from 9 to
// kEffectsStateSize doubles, kViscousStateSize with the Maxwell arm (viscosity_time > 0).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "shard/params.hpp"

namespace shard::beam {

struct BondEffectPolicy {
  std::string name;
  std::string doc;
  std::vector<ParamSpec> params;  // each with its neutral value (strength_seed: none, it is no effect)
};

// The four policies, in the order `effects` lists them in an error.
const std::vector<BondEffectPolicy>& bond_effect_policies();

// The `effects` key and every policy's parameters: what beam_bond's schema adds to the base beam.
std::vector<ParamSpec> bond_effect_params();

struct BondEffects {
  double strength_weibull_modulus = 0;     // m, 1; 0 = every bond has critical_stress
  double strength_cv = 0;                  // the same law given by its scatter (std / mean), 1; 0 = none
  std::uint64_t strength_seed = 0;         // seed of the per-bond strength hash
  double softening_ratio = 0;              // s, 1; fracture energy over peak elastic energy
  double viscosity_time = 0;               // tau_v, s; eta = E_b tau_v
  double viscous_modulus_ratio = 1;        // beta, 1; Maxwell arm modulus beta E_b, relaxation tau_v / beta
  double compression_stiffness_ratio = 1;  // r, 1
  std::vector<std::string> named;          // the policies `effects` lists

  // Reads the policies' parameters and `effects`; an unknown name in `effects` throws, listing the valid ones.
  static BondEffects from(const ParamSet& p);
  // True when a policy is named or any parameter is away from its neutral value.
  bool any() const;
  bool viscous() const { return viscosity_time > 0; }
  // The Weibull modulus in effect: strength_weibull_modulus, or the one of strength_cv; 0 = none.
  double weibull_modulus() const;
};

// Per-bond state of the effects variant: beam_bond's 9 doubles (l0, b1, b2), the bond's strength
// and its damage; with the Maxwell arm also the previous step's (Gamma, kappa) and the arm's
// strains (h_Gamma, h_kappa).
inline constexpr std::size_t kStrengthSlot = 9;
inline constexpr std::size_t kDamageSlot = 10;
inline constexpr std::size_t kEffectsStateSize = 11;
inline constexpr std::size_t kPreviousStrainSlot = 11;  // Gamma (3), then kappa (3)
inline constexpr std::size_t kArmStrainSlot = 17;       // h_Gamma (3), then h_kappa (3)
inline constexpr std::size_t kViscousStateSize = 23;

}  // namespace shard::beam
