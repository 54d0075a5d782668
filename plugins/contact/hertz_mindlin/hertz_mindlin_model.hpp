#pragma once
// Hertz-Mindlin with Coulomb friction, the master contact model of the seed (README.md), with the
// contact effect policies cohesion and support_friction (../common/contact_effects.hpp).
#include <cstddef>
#include <string>
#include <vector>

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
  using ContactModel::time_step_limit;
  TimeStepLimit time_step_limit(double min_radius, double density) const override;
  // Several materials (docs/reference/materials.md): G and nu per material, mu and e per pair; E* and G* of
  // a pair from both materials' moduli (hertz_equations.hpp), the Rayleigh time per material.
  void set_materials(const ContactMaterials& materials) override;
  TimeStepLimit time_step_limit(const std::vector<MaterialExtent>& per_material) const override;
  // The batch in the widest lanes this machine runs (hertz_kernels.hpp); every width gives the same bits.
  void compute(ContactBatch& batch) const override;
  // The same law in the lanes of `set` (tests compare them; scalar is the reference).
  void compute_with(contact::LaneSet set, ContactBatch& batch) const;

  double effective_young_modulus() const { return e_star_; }
  double effective_shear_modulus() const { return g_star_; }
  // Dimensionless c of the dashpot c sqrt(S m*), solved from the restitution.
  double damping() const { return damping_; }
  contact::EffectSwitches effects_on() const { return effects_.on; }
  // The law of the pair of materials a, b (0, 0 with one material).
  const hertz::HertzLaw& law(std::size_t a, std::size_t b) const { return laws_[a * materials_.size() + b]; }

 private:
  HertzMindlinMaterial material_;
  double e_star_;
  double g_star_;
  double damping_;
  // One material per scene material (one from the constructor until set_materials), one law per
  // pair of them: the table the lanes gather from (row a * count + b).
  std::vector<HertzMindlinMaterial> materials_;
  std::vector<std::string> names_;
  std::vector<hertz::HertzLaw> laws_;
  contact::ComposedEffects effects_;
  contact::LawKernel<hertz::HertzLaw> kernel_;
};

}  // namespace shard
