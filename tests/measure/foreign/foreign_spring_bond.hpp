#pragma once
// A bond law of another form than Shard's beam_bond, for the foreign-truth test only
// (docs/explanation/diagnosis.md "Foreign truth"): linear normal, shear, bending and twisting
// springs with stiffnesses given per bond type in N/m and N m/rad (not from a modulus and the
// bond's section), a force-based breakage criterion as in LAMMPS bpm/rotational,
//   (max(F_n, 0) / F_n,c)^2 + (|F_s| / F_s,c)^2 + (|T_b| / T_b,c)^2 + (|T_t| / T_t,c)^2 >= 1,
// viscous damping on the objective relative velocities, and five hidden effects
// (spring_effects.hpp), each off at its neutral value.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shard/bond_model.hpp"
#include "shard/params.hpp"

namespace shard::foreign {

struct SpringBondParams {
  double normal_stiffness = 1.5e4;    // k_n, N/m
  double shear_stiffness = 5e3;       // k_s, N/m
  double bending_stiffness = 2.5e-3;  // k_b, N m/rad
  double twisting_stiffness = 2e-3;   // k_t, N m/rad
  double normal_strength = 1.0;       // F_n,c, N (tension)
  double shear_strength = 0.6;        // F_s,c, N
  double bending_strength = 3e-4;     // T_b,c, N m
  double twisting_strength = 3e-4;    // T_t,c, N m
  double damping_ratio = 0.05;        // zeta of each spring against the pair's reduced mass / inertia
  bool breakage = true;
  double weibull_modulus = 0;         // 0 = no strength scatter (neutral)
  std::uint64_t strength_seed = 0;
  double softening_ratio = 0;         // 0 = brittle (neutral)
  double compression_ratio = 1;       // k_n in compression / k_n, 1 = symmetric (neutral)
  double fatigue_time = 0;            // t_0 of subcritical damage growth, s; 0 = none (neutral)
  double fatigue_exponent = 16;       // n of the damage rate c^n / t_0
  double cohesion_force = 0;          // pull of a failed bond, N; 0 = none (neutral)
  double cohesion_range = 4e-4;       // stretch past which a failed bond's pull ends, m

  static SpringBondParams from(const ParamSet& p);
};

std::vector<ParamSpec> spring_bond_params();

// Per-bond state, in doubles: rest length, the two body-frame directions, the relative
// orientation (x, y, z, w), the strength factor, the largest load ratio reached, the fatigue
// damage and whether the bond has failed into its cohesive pull (1) or is intact (0).
enum StateSlot : std::size_t {
  kRestLength = 0,
  kDirectionFirst = 1,
  kDirectionSecond = 4,
  kRelative = 7,
  kStrengthFactor = 11,
  kPeakRatio = 12,
  kDamage = 13,
  kCohesive = 14,
  kStateSize = 15
};

class SpringBond final : public BondModel {
 public:
  explicit SpringBond(const SpringBondParams& params);
  std::size_t state_size() const override { return kStateSize; }
  void initialize(BondBatch& batch) const override;
  TimeStepLimit time_step_limit(const BondBatch& batch) const override;
  void compute(BondBatch& batch) const override;
  bool writes_every_output() const override { return true; }

 private:
  void compute_bond(BondBatch& batch, std::size_t k) const;
  void fail(BondBatch& batch, std::size_t k, BondFailureMode mode, double stretch, const Vec3& i_to_j) const;
  void compute_cohesive(BondBatch& batch, std::size_t k, double stretch, const Vec3& i_to_j) const;
  SpringBondParams p_;
};

}  // namespace shard::foreign
