#include "hertz_mindlin_plus_model.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "../common/tangential_spring.hpp"
#include "../hertz_mindlin/hertz_damping.hpp"
#include "../hertz_mindlin/hertz_equations.hpp"
#include "contact_cohesion.hpp"

namespace shard::hertz_plus {

HertzMindlinPlusParams HertzMindlinPlusParams::from(const ParamSet& p) {
  return {p.number("shear_modulus"), p.number("poisson_ratio"), p.number("friction"),
          p.number("restitution"),   p.number("wall_friction"), p.number("cohesion_stress")};
}

namespace {

const HertzMindlinPlusParams& checked(const HertzMindlinPlusParams& m) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("hertz_mindlin_plus: ") + what);
  };
  require(m.shear_modulus > 0.0, "shear_modulus must be > 0 Pa");
  require(m.poisson_ratio > -1.0 && m.poisson_ratio <= 0.5, "poisson_ratio must lie in (-1, 0.5]");
  require(m.friction >= 0.0, "friction must be >= 0");
  require(m.restitution > 0.0 && m.restitution <= 1.0, "restitution must lie in (0, 1]");
  require(m.wall_friction >= 0.0 || m.wall_friction == -1.0, "wall_friction must be >= 0, or -1 for the particle friction");
  require(m.cohesion_stress >= 0.0, "cohesion_stress must be >= 0 Pa");
  return m;
}

}  // namespace

HertzMindlinPlus::HertzMindlinPlus(const HertzMindlinPlusParams& params)
    : p_(checked(params)),
      e_star_(hertz::effective_young_modulus(hertz::young_modulus(params.shear_modulus, params.poisson_ratio),
                                             params.poisson_ratio)),
      g_star_(hertz::effective_shear_modulus(params.shear_modulus, params.poisson_ratio)),
      damping_(hertz::damping_for_restitution(params.restitution)),
      wall_friction_(params.wall_friction < 0 ? params.friction : params.wall_friction) {}

std::size_t HertzMindlinPlus::history_size() const { return contact::kTangentialHistorySize; }

TimeStepLimit HertzMindlinPlus::time_step_limit(double min_radius, double density) const {
  const double t_rayleigh = hertz::rayleigh_time(min_radius, density, p_.shear_modulus, p_.poisson_ratio);
  return {"hertz_mindlin_plus Rayleigh time", t_rayleigh, 0.2 * t_rayleigh};
}

void HertzMindlinPlus::compute(ContactBatch& batch) const {
  const bool cohesive = p_.cohesion_stress > 0;
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Vec3& n = batch.normal[k];
    const Vec3& v = batch.velocity[k];
    const double delta = batch.overlap[k];
    const double R = batch.r_eff[k];
    const double m = batch.m_eff[k];
    const bool wall = batch.j[k] < 0;  // j = -1 - wall index

    // Hertz spring and restitution dashpot, never pulling (hertz_mindlin).
    const double s_n = hertz::normal_stiffness(e_star_, R, delta);
    const double f_n = std::max(0.0, hertz::normal_elastic_force(e_star_, R, delta) -
                                         hertz::dashpot(damping_, s_n, m) * v.dot(n));

    // Mindlin spring capped by Coulomb on the repulsive force; supports and pins have their own mu.
    double* history = batch.history + contact::kTangentialHistorySize * k;
    const Vec3 v_t = contact::tangential_part(v, n);
    const Vec3 xi = contact::rotate_onto_tangent_plane(contact::load_spring(history), n) + v_t * batch.dt;
    const double s_t = hertz::tangential_stiffness(g_star_, R, delta);
    const double mu = wall ? wall_friction_ : p_.friction;
    const auto tangential = contact::coulomb_capped_force(xi, v_t, s_t, hertz::dashpot(damping_, s_t, m), mu * f_n);
    contact::store_spring(history, tangential.spring);

    batch.force[k] = f_n * n + tangential.force;
    batch.energy[k] = hertz::normal_elastic_energy(e_star_, R, delta) + contact::spring_energy(s_t, tangential.spring);
    // Cohesion between particles only (not at walls): a pull along -n on i while they touch.
    if (cohesive && !wall) {
      batch.force[k] -= cohesion::cohesive_force(p_.cohesion_stress, R, delta) * n;
      batch.energy[k] += cohesion::cohesive_energy(p_.cohesion_stress, R, delta);
    }
  }
}

}  // namespace shard::hertz_plus
