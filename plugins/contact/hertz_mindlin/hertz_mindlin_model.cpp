#include "hertz_mindlin_model.hpp"

#include <stdexcept>
#include <string>

#include "../common/contact_batch_arrays.hpp"
#include "hertz_damping.hpp"
#include "hertz_equations.hpp"
#include "hertz_kernels.hpp"

namespace shard {

HertzMindlinMaterial HertzMindlinMaterial::from(const ParamSet& params) {
  return {params.number("shear_modulus"), params.number("poisson_ratio"), params.number("friction"),
          params.number("restitution")};
}

namespace {

const HertzMindlinMaterial& checked(const HertzMindlinMaterial& m) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("hertz_mindlin: ") + what);
  };
  require(m.shear_modulus > 0.0, "shear_modulus must be > 0 Pa");
  require(m.poisson_ratio > -1.0 && m.poisson_ratio <= 0.5, "poisson_ratio must lie in (-1, 0.5]");
  require(m.friction >= 0.0, "friction must be >= 0");
  require(m.restitution > 0.0 && m.restitution <= 1.0, "restitution must lie in (0, 1]");
  return m;
}

}  // namespace

HertzMindlin::HertzMindlin(const HertzMindlinMaterial& material, const contact::ContactEffects& effects)
    : material_(checked(material)),
      e_star_(hertz::effective_young_modulus(
          hertz::young_modulus(material.shear_modulus, material.poisson_ratio), material.poisson_ratio)),
      g_star_(hertz::effective_shear_modulus(material.shear_modulus, material.poisson_ratio)),
      damping_(hertz::damping_for_restitution(material.restitution)),
      law_(hertz::HertzLaw::of(e_star_, g_star_, damping_, material.friction)),
      on_(effects.switches()),
      sizes_(effects.sizes(material.friction)),
      kernel_(hertz::hertz_kernel(contact::best_lane_set(), on_)) {}

HertzMindlin HertzMindlin::from(const ParamSet& params) {
  return HertzMindlin(HertzMindlinMaterial::from(params),
                      contact::ContactEffects::from(params, "hertz_mindlin", /*with_cohesion=*/true));
}

std::size_t HertzMindlin::history_size() const { return contact::kTangentialHistorySize; }

TimeStepLimit HertzMindlin::time_step_limit(double min_radius, double density) const {
  const double t_rayleigh =
      hertz::rayleigh_time(min_radius, density, material_.shear_modulus, material_.poisson_ratio);
  return {"hertz_mindlin Rayleigh time", t_rayleigh, 0.2 * t_rayleigh};
}

void HertzMindlin::compute(ContactBatch& batch) const { kernel_(contact::arrays_of(batch), law_, sizes_); }

void HertzMindlin::compute_with(contact::LaneSet set, ContactBatch& batch) const {
  if (!contact::lane_set_available(set))
    throw std::invalid_argument(std::string("hertz_mindlin: this machine cannot run the ") +
                                std::string(contact::lane_set_name(set)) + " lanes");
  hertz::hertz_kernel(set, on_)(contact::arrays_of(batch), law_, sizes_);
}

}  // namespace shard
