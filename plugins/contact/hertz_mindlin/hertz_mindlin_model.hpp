#pragma once
// Hertz-Mindlin with Coulomb friction, the master contact model of the seed (README.md).
#include <cstddef>

#include "shard/contact_model.hpp"
#include "shard/params.hpp"

namespace shard {

struct HertzMindlinMaterial {
  double shear_modulus = 10e6;  // G, Pa (seed Table I, reduced)
  double poisson_ratio = 0.25;  // nu, 1
  double friction = 0.67;       // mu, 1 (seed Table I)
  double restitution = 0.5;     // e, 1

  static HertzMindlinMaterial from(const ParamSet& params);
};

class HertzMindlin final : public ContactModel {
 public:
  explicit HertzMindlin(const HertzMindlinMaterial& material);

  std::size_t history_size() const override;
  TimeStepLimit time_step_limit(double min_radius, double density) const override;
  // The batch in SIMD lanes (hertz_lanes.hpp), bit-identical to compute_reference.
  void compute(ContactBatch& batch) const override;
  // One contact at a time through the equation helpers, as hertz_mindlin_plus computes them.
  void compute_reference(ContactBatch& batch) const;

  double effective_young_modulus() const { return e_star_; }
  double effective_shear_modulus() const { return g_star_; }
  // Dimensionless c of the dashpot c sqrt(S m*), solved from the restitution.
  double damping() const { return damping_; }

 private:
  HertzMindlinMaterial material_;
  double e_star_;
  double g_star_;
  double damping_;
};

}  // namespace shard
