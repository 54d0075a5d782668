#include "hertz_mindlin_model.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "../common/tangential_spring.hpp"
#include "hertz_damping.hpp"
#include "hertz_equations.hpp"
#include "hertz_lanes.hpp"

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

HertzMindlin::HertzMindlin(const HertzMindlinMaterial& material)
    : material_(checked(material)),
      e_star_(hertz::effective_young_modulus(
          hertz::young_modulus(material.shear_modulus, material.poisson_ratio), material.poisson_ratio)),
      g_star_(hertz::effective_shear_modulus(material.shear_modulus, material.poisson_ratio)),
      damping_(hertz::damping_for_restitution(material.restitution)) {}

std::size_t HertzMindlin::history_size() const { return contact::kTangentialHistorySize; }

TimeStepLimit HertzMindlin::time_step_limit(double min_radius, double density) const {
  const double t_rayleigh =
      hertz::rayleigh_time(min_radius, density, material_.shear_modulus, material_.poisson_ratio);
  return {"hertz_mindlin Rayleigh time", t_rayleigh, 0.2 * t_rayleigh};
}

void HertzMindlin::compute(ContactBatch& batch) const {
  hertz::compute_lanes(batch, {e_star_, g_star_, damping_, material_.friction});
}

void HertzMindlin::compute_reference(ContactBatch& batch) const {
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Vec3& n = batch.normal[k];
    const Vec3& v = batch.velocity[k];
    const double delta = batch.overlap[k];
    const double R = batch.r_eff[k];
    const double m = batch.m_eff[k];

    // Normal: Hertz spring and dashpot; v.n < 0 while approaching, so the dashpot then pushes.
    const double s_n = hertz::normal_stiffness(e_star_, R, delta);
    const double f_n = std::max(0.0, hertz::normal_elastic_force(e_star_, R, delta) -
                                         hertz::dashpot(damping_, s_n, m) * v.dot(n));

    // Tangential: the spring turns with the contact plane, stretches with the sliding velocity.
    double* history = batch.history + contact::kTangentialHistorySize * k;
    const Vec3 v_t = contact::tangential_part(v, n);
    const Vec3 xi = contact::rotate_onto_tangent_plane(contact::load_spring(history), n) + v_t * batch.dt;
    const double s_t = hertz::tangential_stiffness(g_star_, R, delta);
    const auto tangential = contact::coulomb_capped_force(xi, v_t, s_t, hertz::dashpot(damping_, s_t, m),
                                                          material_.friction * f_n);
    contact::store_spring(history, tangential.spring);

    batch.force[k] = f_n * n + tangential.force;
    batch.energy[k] = hertz::normal_elastic_energy(e_star_, R, delta) +
                      contact::spring_energy(s_t, tangential.spring);
  }
}

}  // namespace shard
