#pragma once
// Hertz-Mindlin with Coulomb friction, the master contact model of the seed (README.md), with the
// contact effect policies cohesion and support_friction (../common/contact_effects.hpp).
#include <cstddef>

#include "../common/contact_effects.hpp"
#include "../common/lane_sets.hpp"
#include "hertz_law.hpp"
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
  explicit HertzMindlin(const HertzMindlinMaterial& material, const contact::ContactEffects& effects = {});
  static HertzMindlin from(const ParamSet& params);

  std::size_t history_size() const override;
  TimeStepLimit time_step_limit(double min_radius, double density) const override;
  // The batch in the widest lanes this machine runs (hertz_kernels.hpp); every width gives the same bits.
  void compute(ContactBatch& batch) const override;
  // The same law in the lanes of `set` (tests compare them; scalar is the reference).
  void compute_with(contact::LaneSet set, ContactBatch& batch) const;

  double effective_young_modulus() const { return e_star_; }
  double effective_shear_modulus() const { return g_star_; }
  // Dimensionless c of the dashpot c sqrt(S m*), solved from the restitution.
  double damping() const { return damping_; }
  contact::EffectSwitches effects_on() const { return on_; }

 private:
  HertzMindlinMaterial material_;
  double e_star_;
  double g_star_;
  double damping_;
  hertz::HertzLaw law_;
  contact::EffectSwitches on_;
  contact::EffectSizes sizes_;
  contact::LawKernel<hertz::HertzLaw> kernel_;
};

}  // namespace shard
