#pragma once
// Linear spring-dashpot with Coulomb friction: the cheap baseline contact model (README.md),
// with the contact effect policy support_friction (../common/contact_effects.hpp).
#include <cstddef>
#include <string>
#include <vector>

#include "../common/contact_effects.hpp"
#include "../common/lane_sets.hpp"
#include "linear_law.hpp"
#include "shard/contact_model.hpp"
#include "shard/params.hpp"

namespace shard {

struct LinearSpringParameters {
  double normal_stiffness = 1e3;              // k_n, N/m
  double tangential_stiffness_ratio = 2.0 / 7.0;  // k_t / k_n, 1
  double friction = 0.67;                     // mu, 1
  double restitution = 0.5;                   // e, 1

  static LinearSpringParameters from(const ParamSet& params);
};

class LinearSpring final : public ContactModel {
 public:
  explicit LinearSpring(const LinearSpringParameters& parameters, const contact::ContactEffects& effects = {});
  static LinearSpring from(const ParamSet& params);

  std::size_t history_size() const override;
  using ContactModel::time_step_limit;
  TimeStepLimit time_step_limit(double min_radius, double density) const override;
  // Several materials (docs/reference/materials.md): every parameter is per pair (a spring has no mixing
  // rule); the time step from the stiffest pair on its lightest particles.
  void set_materials(const ContactMaterials& materials) override;
  TimeStepLimit time_step_limit(const std::vector<MaterialExtent>& per_material) const override;
  // The batch in the widest lanes this machine runs (linear_kernels.hpp); every width gives the same bits.
  void compute(ContactBatch& batch) const override;
  // The same law in the lanes of `set` (tests compare them; scalar is the reference).
  void compute_with(contact::LaneSet set, ContactBatch& batch) const;

  double normal_stiffness() const { return k_n_; }
  double tangential_stiffness() const { return k_t_; }
  // Damping ratio zeta of both dashpots, solved from the restitution.
  double damping_ratio() const { return zeta_; }
  contact::EffectSwitches effects_on() const { return effects_.on; }
  // The law of the pair of materials a, b (0, 0 with one material).
  const linear::LinearLaw& law(std::size_t a, std::size_t b) const { return laws_[a * count_ + b]; }

 private:
  double k_n_;
  double k_t_;
  double friction_;
  double zeta_;
  // One law per pair of materials, the table the lanes gather from (row a * count + b).
  std::size_t count_ = 1;
  std::vector<std::string> names_{""};
  std::vector<linear::LinearLaw> laws_;
  contact::ComposedEffects effects_;
  contact::LawKernel<linear::LinearLaw> kernel_;
};

}  // namespace shard
