// Contact effect policies of hertz_mindlin (plugins/contact/common/contact_effects.hpp): friction of
// its own at walls (support_friction), and cohesion between touching particles (pull per contact
// area; pull-off force of the Hertz + cohesion law); support_friction of linear_spring.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact_batch.hpp"
#include "sphere_on_plane.hpp"
#include "hertz_mindlin_model.hpp"
#include "linear_spring_model.hpp"
#include "shard/simulation.hpp"

namespace shard::effects_test {
namespace {

HertzMindlin hertz(double friction, double support_ratio, double cohesion_stress) {
  HertzMindlinMaterial m;
  m.friction = friction;
  contact::ContactEffects e;
  e.support_friction_ratio = support_ratio;
  e.cohesion_stress = cohesion_stress;
  return HertzMindlin(m, e);
}

}  // namespace

TEST_CASE("a sphere sliding on a wall decelerates at mu_wall g, independent of the particle friction") {
  const double friction = 0.67;
  for (const double ratio : {0.2 / 0.67, 1.0}) {
    const HertzMindlin model = hertz(friction, ratio, 0);
    CHECK(model.effects_on().support_friction == (ratio != 1.0));
    const double mu = ratio * friction;
    const double mu_wall = mu;
    SphereOnPlane s(model, model.effective_young_modulus());
    // Sliding lasts until v = 5/7 v0 at t = 2 v0 / (7 mu g): 7.3 ms for mu = 0.2, 2.2 ms for 0.67.
    const double t_roll = 2 * SphereOnPlane::v0 / (7 * mu * SphereOnPlane::g);
    const double t1 = 0.1 * t_roll, t2 = 0.8 * t_roll;
    const double v1 = s.velocity_at(t1), v2 = s.velocity_at(t2);
    const double deceleration = (v1 - v2) / (t2 - t1);
    MESSAGE("mu_wall ", mu_wall, ": deceleration ", deceleration, " m/s^2 vs mu g = ", mu * SphereOnPlane::g);
    // The normal force rings around m g from the start (restitution 0.5 damps it); 1 % covers it.
    CHECK(deceleration == doctest::Approx(mu * SphereOnPlane::g).epsilon(0.01));
    // And after rolling sets in: v = 5/7 v0 (rolling without slip; rolling friction absent).
    CHECK(s.velocity_at(1.5 * t_roll) == doctest::Approx(5.0 / 7 * SphereOnPlane::v0).epsilon(0.01).scale(0));
  }
}

TEST_CASE("wall friction at the batch level: |F_t| = mu_wall F_n at walls, mu F_n between particles") {
  const HertzMindlin hertz_model = hertz(0.5, 0.2, 0);
  LinearSpringParameters lp;
  lp.friction = 0.5;
  contact::ContactEffects support;
  support.support_friction_ratio = 0.2;
  const LinearSpring linear_model(lp, support);
  for (const ContactModel* model : {static_cast<const ContactModel*>(&hertz_model),
                                    static_cast<const ContactModel*>(&linear_model)}) {
  ContactScene c(2, model->history_size());
  c.j = {-1, 1};
  for (std::size_t k = 0; k < 2; ++k) {
    c.overlap[k] = 1e-6;
    c.r_eff[k] = 0.35e-3;
    c.m_eff[k] = 1e-6;
    c.velocity[k] = Vec3(0.01, 0, 0);  // steady sliding along x
  }
  for (int step = 0; step < 200; ++step) c.compute(*model, 1e-6);
  for (std::size_t k = 0; k < 2; ++k) {
    const double f_n = c.force[k].z();
    const Vec3 f_t(c.force[k].x(), c.force[k].y(), 0);
    // At the cap |F_t| = mu F_n up to the rounding of the scaling (a few ulp).
    CHECK(f_t.norm() / f_n == doctest::Approx(k == 0 ? 0.2 * 0.5 : 0.5).epsilon(1e-12));
    CHECK(f_t.x() < 0);  // opposes the sliding
  }
  }
}

TEST_CASE("cohesion: pull sigma_c pi R delta between particles, none at walls, energy its potential") {
  const HertzMindlin model = hertz(0.67, 1, 20e3);  // Pa
  const HertzMindlin dry = hertz(0.67, 1, 0);
  const double R = 0.175e-3, delta = 2e-7;
  ContactScene c(2, model.history_size()), d(2, dry.history_size());
  c.j = d.j = {1, -1};
  for (auto* s : {&c, &d}) {
    s->overlap = {delta, delta};
    s->r_eff = {R, R};
    s->m_eff = {1e-6, 1e-6};
  }
  c.compute(model, 1e-6);
  d.compute(dry, 1e-6);
  CHECK(d.force[0].z() - c.force[0].z() == doctest::Approx(20e3 * std::numbers::pi * R * delta).epsilon(1e-12));
  CHECK(c.force[1].z() == d.force[1].z());  // wall: no cohesion
  CHECK(d.energy[0] - c.energy[0] == doctest::Approx(0.5 * 20e3 * std::numbers::pi * R * delta * delta).epsilon(1e-12).scale(0));

  // The force is minus the derivative of the energy (central difference, zero velocity).
  const double h = 1e-11;
  c.overlap[0] = delta + h;
  c.compute(model, 1e-6);
  const double u_plus = c.energy[0];
  c.overlap[0] = delta - h;
  c.compute(model, 1e-6);
  const double u_minus = c.energy[0];
  c.overlap[0] = delta;
  c.compute(model, 1e-6);
  CHECK(c.force[0].z() == doctest::Approx((u_plus - u_minus) / (2 * h)).epsilon(1e-6).scale(0));
}

TEST_CASE("cohesion: the most attractive force over the overlap is the pull-off force (pi sigma_c)^3 R^2 / (12 E*^2)") {
  const double cohesion_stress = 50e3;
  const HertzMindlin model = hertz(0.67, 1, cohesion_stress);
  const double R = 0.175e-3;
  const double e_star = model.effective_young_modulus();
  const double delta_star = std::pow(std::numbers::pi * cohesion_stress, 2) * R / (4 * e_star * e_star);
  ContactScene c(1, model.history_size());
  c.r_eff[0] = R;
  c.m_eff[0] = 1e-6;
  double most_attractive = 0, at = 0;
  for (int n = 1; n <= 4000; ++n) {
    c.overlap[0] = 4 * delta_star * n / 4000;
    c.compute(model, 1e-6);
    if (c.force[0].z() < most_attractive) most_attractive = c.force[0].z(), at = c.overlap[0];
  }
  const double pull_off = contact::pull_off_force(cohesion_stress, R, e_star);
  MESSAGE("pull-off ", -most_attractive, " N at delta ", at, " m; theory ", pull_off, " N at ", delta_star, " m");
  CHECK(-most_attractive == doctest::Approx(pull_off).epsilon(1e-6).scale(0));  // flat minimum: grid error O(h^2)
  CHECK(at == doctest::Approx(delta_star).epsilon(2e-3).scale(0));
  // Repulsive again beyond the equilibrium overlap (3 pi sigma_c sqrt(R) / (4 E*))^2 = 9/4 delta*.
  c.overlap[0] = 2.25 * delta_star * 1.01;
  c.compute(model, 1e-6);
  CHECK(c.force[0].z() > 0);
  c.overlap[0] = 2.25 * delta_star * 0.99;
  c.compute(model, 1e-6);
  CHECK(c.force[0].z() < 0);
}

}  // namespace shard::effects_test
