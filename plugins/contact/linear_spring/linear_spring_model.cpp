#include "linear_spring_model.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>
#include <string>

#include "../common/tangential_spring.hpp"
#include "linear_damping.hpp"
#include "linear_equations.hpp"

namespace shard {

LinearSpringParameters LinearSpringParameters::from(const ParamSet& params) {
  return {params.number("normal_stiffness"), params.number("tangential_stiffness_ratio"),
          params.number("friction"), params.number("restitution")};
}

namespace {

const LinearSpringParameters& checked(const LinearSpringParameters& p) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("linear_spring: ") + what);
  };
  require(p.normal_stiffness > 0.0, "normal_stiffness must be > 0 N/m");
  require(p.tangential_stiffness_ratio > 0.0, "tangential_stiffness_ratio must be > 0");
  require(p.friction >= 0.0, "friction must be >= 0");
  require(p.restitution > 0.0 && p.restitution <= 1.0, "restitution must lie in (0, 1]");
  return p;
}

}  // namespace

LinearSpring::LinearSpring(const LinearSpringParameters& parameters)
    : k_n_(checked(parameters).normal_stiffness),
      k_t_(parameters.tangential_stiffness_ratio * parameters.normal_stiffness),
      friction_(parameters.friction),
      zeta_(linear::damping_ratio_for_restitution(parameters.restitution)) {}

std::size_t LinearSpring::history_size() const { return contact::kTangentialHistorySize; }

// The shortest contact in a scene is between the two lightest particles (m* = m/2), and the
// stiffer of the normal and rolling-tangential oscillators sets its pace. The step is t_c / 20
// (docs/physics.md, Time step): stable and accurate for the spring, but the kernel's velocity Verlet feeds
// the dashpot the half-step velocity, so the realised restitution comes out high by about
// 5 % (e = 0.3), 3 % (e = 0.5), 1 % (e = 0.9); it falls in proportion to dt (tests/contact).
TimeStepLimit LinearSpring::time_step_limit(double min_radius, double density) const {
  const double lightest = density * 4.0 / 3.0 * std::numbers::pi * min_radius * min_radius * min_radius;
  const double t_contact = linear::contact_duration(linear::stiffest_oscillator(k_n_, k_t_), 0.5 * lightest);
  return {"linear_spring contact duration", t_contact, t_contact / 20.0};
}

void LinearSpring::compute(ContactBatch& batch) const {
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Vec3& n = batch.normal[k];
    const Vec3& v = batch.velocity[k];
    const double delta = batch.overlap[k];
    const double m = batch.m_eff[k];

    // Normal: spring and dashpot; v.n < 0 while approaching, so the dashpot then pushes.
    const double f_n =
        std::max(0.0, linear::normal_elastic_force(k_n_, delta) - linear::dashpot(zeta_, k_n_, m) * v.dot(n));

    // Tangential: the spring turns with the contact plane, stretches with the sliding velocity.
    double* history = batch.history + contact::kTangentialHistorySize * k;
    const Vec3 v_t = contact::tangential_part(v, n);
    const Vec3 xi = contact::rotate_onto_tangent_plane(contact::load_spring(history), n) + v_t * batch.dt;
    const auto tangential =
        contact::coulomb_capped_force(xi, v_t, k_t_, linear::dashpot(zeta_, k_t_, m), friction_ * f_n);
    contact::store_spring(history, tangential.spring);

    batch.force[k] = f_n * n + tangential.force;
    batch.energy[k] = linear::normal_elastic_energy(k_n_, delta) + contact::spring_energy(k_t_, tangential.spring);
  }
}

}  // namespace shard
