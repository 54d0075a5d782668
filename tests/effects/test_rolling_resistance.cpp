// Rolling resistance, the contact policy rolling_resistance (plugins/contact/common/contact_lanes.hpp):
// a couple against the relative rolling spin, an elastic-plastic spring-dashpot k_r = S_t R*^2,
// c_r = c_t R*^2 capped at mu_r R* F_n. At the cap a sphere rolling on a plane decelerates at
// a = mu_r R F_n R / (I + m R^2) = 5/7 mu_r g (I = 2/5 m R^2) and stops after v0^2 / (2 a).
#include <doctest/doctest.h>

#include <cmath>

#include "contact_batch.hpp"
#include "hertz_mindlin_model.hpp"
#include "linear_spring_model.hpp"
#include "sphere_on_plane.hpp"

namespace shard::effects_test {
namespace {

contact::ContactEffects rolling(double mu_r, bool named = false) {
  contact::ContactEffects e;
  e.rolling_friction = mu_r;
  if (named) e.named = {"rolling_resistance"};
  return e;
}

// Deceleration between 10 % and 80 % of the stopping time, the rest after 1.5 of it, and the
// distance rolled, for one law.
void check_rolls_to_rest(const ContactModel& model, double e_star, double mu_r) {
  CAPTURE(mu_r);
  SphereOnPlane s(model, e_star, /*rolling=*/true);
  const double a = 5.0 / 7.0 * mu_r * SphereOnPlane::g;
  const double t_stop = SphereOnPlane::v0 / a;
  const double t1 = 0.1 * t_stop, t2 = 0.8 * t_stop;
  const double v1 = s.velocity_at(t1), v2 = s.velocity_at(t2);
  const double deceleration = (v1 - v2) / (t2 - t1);
  MESSAGE("mu_r ", mu_r, ": deceleration ", deceleration, " m/s^2 against 5/7 mu_r g = ", a);
  // The normal force rings around m g at the start (restitution 0.5 damps it): 1 %, as for sliding.
  CHECK(deceleration == doctest::Approx(a).epsilon(0.01).scale(0));
  // Still rolling without slip: the contact point's speed is a small share of the sphere's.
  const Particles& p = s.sim->particles();
  const double slip = (p.velocity[0] + p.omega[0].cross(Vec3(0, 0, -SphereOnPlane::radius))).norm();
  CHECK(slip < 1e-3 * std::abs(v2));
  s.run_to(1.5 * t_stop);
  const double rolled = p.position[0].x();
  CHECK(rolled == doctest::Approx(SphereOnPlane::v0 * SphereOnPlane::v0 / (2 * a)).epsilon(0.01).scale(0));
  // At rest, and it stays there: what the rolling spring still rocks decays (c_r).
  CHECK(std::abs(p.velocity[0].x()) < 1e-4 * SphereOnPlane::v0);
  s.run_to(2.0 * t_stop);
  CHECK(std::abs(p.velocity[0].x()) < 1e-5 * SphereOnPlane::v0);
  CHECK(p.position[0].x() == doctest::Approx(rolled).epsilon(1e-4).scale(0));
}

}  // namespace

TEST_CASE("rolling resistance: a sphere rolling on a plane decelerates at 5/7 mu_r g and comes to rest") {
  for (const double mu_r : {0.05, 0.2}) {
    const HertzMindlin model(HertzMindlinMaterial{}, rolling(mu_r));
    REQUIRE(model.effects_on().rolling_resistance);
    CHECK(model.history_size() == contact::kRollingHistorySize);
    check_rolls_to_rest(model, model.effective_young_modulus(), mu_r);
  }
  LinearSpringParameters spring;
  spring.normal_stiffness = 2e4;  // N/m: the 1 mm sphere's weight compresses it by 2 um
  const LinearSpring linear(spring, rolling(0.1));
  check_rolls_to_rest(linear, 0.0, 0.1);
}

TEST_CASE("rolling resistance off: a rolling sphere keeps rolling; named at mu_r = 0 it changes no bit") {
  const HertzMindlin plain(HertzMindlinMaterial{});
  const HertzMindlin named(HertzMindlinMaterial{}, rolling(0.0, /*named=*/true));
  CHECK_FALSE(plain.effects_on().rolling_resistance);
  CHECK(named.effects_on().rolling_resistance);
  SphereOnPlane a(plain, plain.effective_young_modulus(), true), b(named, named.effective_young_modulus(), true);
  a.run_to(0.05);
  b.run_to(0.05);
  // Rolling without slip dissipates nothing: 50 ms later it rolls at v0 (measured -1.2e-4 of it,
  // lost while the normal spring rings in at the start; mu_r = 0.05 would have taken 35 %).
  CHECK(a.sim->particles().velocity[0].x() == doctest::Approx(SphereOnPlane::v0).epsilon(1e-3).scale(0));
  for (int c = 0; c < 3; ++c) {
    CHECK(a.sim->particles().position[0][c] == b.sim->particles().position[0][c]);
    CHECK(a.sim->particles().velocity[0][c] == b.sim->particles().velocity[0][c]);
    CHECK(a.sim->particles().omega[0][c] == b.sim->particles().omega[0][c]);
  }
}

TEST_CASE("rolling couple: elastic step -k_r w dt - c_r w, cap mu_r R* F_n against the rolling spin, no twist") {
  const double mu_r = 0.3, R = 0.5e-3, delta = 2e-6, m = 1e-5, dt = 1e-7, w = 2.0;
  const HertzMindlin model(HertzMindlinMaterial{}, rolling(mu_r));
  ContactScene c(2, model.history_size());
  c.j = {1, -1};
  c.overlap = {delta, delta};
  c.r_eff = {R, R};
  c.m_eff = {m, m};
  // Contact 0 rolls about y and twists about its normal z; contact 1 (a wall) only twists.
  c.omega_rel = {Vec3(0, w, 5.0), Vec3(0, 0, 7.0)};
  c.compute(model, dt);
  const double s_t = 8 * model.effective_shear_modulus() * std::sqrt(R * delta);
  const double c_t = model.damping() * std::sqrt(s_t * m);
  const double k_r = s_t * R * R, c_r = c_t * R * R;
  CHECK(c.couple[0].y() == doctest::Approx(-k_r * w * dt - c_r * w).epsilon(1e-12).scale(0));
  CHECK(c.couple[0].x() == 0.0);
  CHECK(c.couple[0].z() == 0.0);
  CHECK(c.couple[1].norm() == 0.0);
  // Wound on, the spring reaches the cap and holds it.
  for (int step = 0; step < 20000; ++step) c.compute(model, dt);
  const double f_n = c.force[0].z();
  CHECK(c.couple[0].y() == doctest::Approx(-mu_r * R * f_n).epsilon(1e-12).scale(0));
  CHECK(c.couple[0].x() == 0.0);
  // The energy holds the spring's k_r theta^2 / 2 with theta = M / k_r at the cap.
  ContactScene plain(1, 3);
  plain.overlap = {delta};
  plain.r_eff = {R};
  plain.m_eff = {m};
  plain.compute(HertzMindlin(HertzMindlinMaterial{}), dt);
  const double m_cap = mu_r * R * f_n;
  CHECK(c.energy[0] - plain.energy[0] == doctest::Approx(m_cap * m_cap / (2 * k_r)).epsilon(1e-9).scale(0));
}

}  // namespace shard::effects_test
