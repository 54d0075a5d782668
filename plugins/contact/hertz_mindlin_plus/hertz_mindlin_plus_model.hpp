#pragma once
// hertz_mindlin with two effects a measurement may show missing (docs/effects.md), each with a
// neutral value at which this model runs exactly the arithmetic of hertz_mindlin:
//   wall_friction mu_w      -1  Coulomb coefficient at particle-wall contacts (supports, pins);
//                               -1 = the particle friction
//   cohesion_stress sigma_c  0  Pa, pull per contact area between touching particles
#include <cstddef>

#include "shard/contact_model.hpp"
#include "shard/params.hpp"

namespace shard::hertz_plus {

struct HertzMindlinPlusParams {
  double shear_modulus = 10e6;  // G, Pa
  double poisson_ratio = 0.25;  // nu, 1
  double friction = 0.67;       // mu, 1
  double restitution = 0.5;     // e, 1
  double wall_friction = -1;    // mu_w, 1; < 0 = friction
  double cohesion_stress = 0;   // sigma_c, Pa

  static HertzMindlinPlusParams from(const ParamSet& p);
};

class HertzMindlinPlus final : public ContactModel {
 public:
  explicit HertzMindlinPlus(const HertzMindlinPlusParams& params);

  std::size_t history_size() const override;
  TimeStepLimit time_step_limit(double min_radius, double density) const override;
  void compute(ContactBatch& batch) const override;

  double effective_young_modulus() const { return e_star_; }
  double wall_friction() const { return wall_friction_; }

 private:
  HertzMindlinPlusParams p_;
  double e_star_, g_star_, damping_;
  double wall_friction_;  // resolved: mu_w, or mu when unset
};

}  // namespace shard::hertz_plus
