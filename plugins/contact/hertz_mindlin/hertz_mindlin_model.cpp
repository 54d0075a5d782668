#include "hertz_mindlin_model.hpp"

#include <stdexcept>
#include <string>
#include <utility>

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
      materials_{material},
      names_{""},
      laws_{hertz::HertzLaw::of(e_star_, g_star_, damping_, material.friction)},
      effects_(effects),
      kernel_(hertz::hertz_kernel(contact::best_lane_set(), effects_.on)) {}

HertzMindlin HertzMindlin::from(const ParamSet& params) {
  return HertzMindlin(HertzMindlinMaterial::from(params),
                      contact::ContactEffects::from(params, "hertz_mindlin", /*with_cohesion=*/true));
}

std::size_t HertzMindlin::history_size() const { return effects_.history_size(); }

TimeStepLimit HertzMindlin::time_step_limit(double min_radius, double density) const {
  // The first material's (the only one, unless set_materials gave a table of one).
  const double t_rayleigh =
      hertz::rayleigh_time(min_radius, density, materials_[0].shear_modulus, materials_[0].poisson_ratio);
  return {"hertz_mindlin Rayleigh time", t_rayleigh, 0.2 * t_rayleigh};
}

void HertzMindlin::set_materials(const ContactMaterials& m) {
  const std::size_t n = m.count;
  if (n == 0 || m.material.size() != n || m.pair.size() != n * n || m.names.size() != n)
    throw std::invalid_argument("hertz_mindlin: a material table needs one entry per material and per pair");
  std::vector<HertzMindlinMaterial> materials(n);
  for (std::size_t a = 0; a < n; ++a) {
    materials[a].shear_modulus = m.material[a].number("shear_modulus");
    materials[a].poisson_ratio = m.material[a].number("poisson_ratio");
  }
  std::vector<hertz::HertzLaw> laws(n * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const ParamSet& pair = m.pair[a * n + b];
      const HertzMindlinMaterial& A = materials[a];
      const HertzMindlinMaterial& B = materials[b];
      try {
        checked({A.shear_modulus, A.poisson_ratio, pair.number("friction"), pair.number("restitution")});
        checked({B.shear_modulus, B.poisson_ratio, pair.number("friction"), pair.number("restitution")});
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string(e.what()) + " (materials '" + m.names[a] + "' and '" + m.names[b] + "')");
      }
      // One material: the alike forms, bit for bit those of the one-material constructor.
      const double e_star =
          a == b ? hertz::effective_young_modulus(hertz::young_modulus(A.shear_modulus, A.poisson_ratio), A.poisson_ratio)
                 : hertz::mixed_young_modulus(hertz::young_modulus(A.shear_modulus, A.poisson_ratio), A.poisson_ratio,
                                              hertz::young_modulus(B.shear_modulus, B.poisson_ratio), B.poisson_ratio);
      const double g_star = a == b ? hertz::effective_shear_modulus(A.shear_modulus, A.poisson_ratio)
                                   : hertz::mixed_shear_modulus(A.shear_modulus, A.poisson_ratio, B.shear_modulus,
                                                                B.poisson_ratio);
      laws[a * n + b] = hertz::HertzLaw::of(e_star, g_star, hertz::damping_for_restitution(pair.number("restitution")),
                                            pair.number("friction"));
    }
  materials_ = std::move(materials);
  names_ = m.names;
  laws_ = std::move(laws);
  effects_.set_pairs(m.pair);
  kernel_ = hertz::hertz_kernel(contact::best_lane_set(), effects_.on);
}

TimeStepLimit HertzMindlin::time_step_limit(const std::vector<MaterialExtent>& per_material) const {
  TimeStepLimit out{"hertz_mindlin Rayleigh time", 0, 0};
  bool any = false;
  for (std::size_t a = 0; a < per_material.size() && a < materials_.size(); ++a) {
    if (!(per_material[a].min_radius > 0)) continue;
    const double t = hertz::rayleigh_time(per_material[a].min_radius, per_material[a].density,
                                          materials_[a].shear_modulus, materials_[a].poisson_ratio);
    if (any && !(t < out.critical)) continue;
    any = true;
    out = {names_[a].empty() ? "hertz_mindlin Rayleigh time" : "hertz_mindlin Rayleigh time (" + names_[a] + ")", t,
           0.2 * t};
  }
  return out;
}

void HertzMindlin::compute(ContactBatch& batch) const { kernel_(contact::arrays_of(batch), laws_.data(), effects_.sizes()); }

void HertzMindlin::compute_with(contact::LaneSet set, ContactBatch& batch) const {
  hertz::hertz_kernel.required(set, effects_.on, "hertz_mindlin")(contact::arrays_of(batch), laws_.data(), effects_.sizes());
}

}  // namespace shard
