// Hertz-Mindlin plugin: force law, restitution, friction, tangential history, time step.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <initializer_list>
#include <numbers>

#include "contact_arrays.hpp"
#include "contact_plugins.hpp"
#include "head_on_collision.hpp"
#include "table_one.hpp"

using namespace shard;
using namespace shard::test;

namespace {

std::unique_ptr<ContactModel> table_one_model(const ContactPlugins& plugins, double restitution = 0.5,
                                              double friction = table_one::friction) {
  return plugins.make("hertz_mindlin", {{"shear_modulus", table_one::shear_modulus},
                                        {"poisson_ratio", table_one::poisson_ratio},
                                        {"friction", friction},
                                        {"restitution", restitution}});
}

double hertz_force(double r_eff, double delta) {
  return 4.0 / 3.0 * table_one::e_star() * std::sqrt(r_eff) * std::pow(delta, 1.5);
}

}  // namespace

TEST_CASE("hertz_mindlin declares its parameters with SI units, defaults and ranges") {
  const ContactPlugins plugins;
  const PluginInfo& info = plugins.info("hertz_mindlin");
  CHECK(info.kind == PluginKind::Contact);
  // The law's four, then `effects` and its policies' parameters (docs/reference/effects.md).
  REQUIRE(info.params.size() == 8);
  const std::array<const char*, 7> names{"shear_modulus",   "poisson_ratio",          "friction",        "restitution",
                                         "cohesion_stress", "support_friction_ratio", "rolling_friction"};
  const std::array<const char*, 7> units{"Pa", "1", "1", "1", "Pa", "1", "1"};
  const std::array<double, 7> defaults{10e6, 0.25, 0.67, 0.5, 0.0, 1.0, 0.0};
  for (std::size_t k = 0; k < 7; ++k) {
    const ParamSpec& spec = info.params[k < 4 ? k : k + 1];
    CHECK(spec.name == names[k]);
    CHECK(spec.unit == units[k]);
    CHECK(std::get<double>(spec.default_value) == defaults[k]);
  }
  CHECK(info.params[4].name == "effects");
  CHECK(info.params[5].neutral == 0.0);
  CHECK(info.params[6].neutral == 1.0);
  CHECK(info.params[7].neutral == 0.0);
  CHECK(info.params[7].scope == ParamScope::Pair);
  CHECK_THROWS_AS(plugins.make("hertz_mindlin", {{"cohesion_stress", -1.0}}), PluginError);
  CHECK_THROWS_AS(plugins.make("hertz_mindlin", {{"rolling_friction", -0.1}}), PluginError);
  CHECK_THROWS_AS(plugins.make("hertz_mindlin", {{"restitution", 0.0}}), PluginError);
  CHECK_THROWS_AS(plugins.make("hertz_mindlin", {{"shear_modulus", 0.0}}), PluginError);
  CHECK_THROWS_AS(plugins.make("hertz_mindlin", {{"poisson_ratio", 0.6}}), PluginError);
  CHECK_THROWS_AS(plugins.make("hertz_mindlin", {{"friction", -0.1}}), PluginError);
}

TEST_CASE("hertz normal force and energy equal 4/3 E* sqrt(R*) delta^1.5 and 8/15 E* sqrt(R*) delta^2.5") {
  const ContactPlugins plugins;
  const auto model = table_one_model(plugins);
  // Particle-particle pairs of equal and unequal spheres, and a particle-wall contact (R* = r).
  const std::array<double, 4> r_eff{0.175e-3, 0.2e-3, 0.35e-3, 1e-2};
  const std::array<double, 4> delta{1e-9, 3.5e-6, 2e-5, 1e-3};
  ContactArrays c(r_eff.size(), model->history_size());
  for (std::size_t k = 0; k < r_eff.size(); ++k) {
    c.j[k] = k == 2 ? -1 : Index(k + 1);
    c.normal[k] = Vec3(1.0, 2.0, -2.0) / 3.0;
    c.overlap[k] = delta[k];
    c.r_eff[k] = r_eff[k];
    c.m_eff[k] = 1e-6;
  }
  ContactBatch batch = c.batch(1e-6);
  model->compute(batch);
  for (std::size_t k = 0; k < r_eff.size(); ++k) {
    CAPTURE(k);
    const double expected = hertz_force(r_eff[k], delta[k]);
    CHECK(relative_difference(c.force[k].dot(c.normal[k]), expected) <= 1e-12);
    CHECK((c.force[k] - c.force[k].dot(c.normal[k]) * c.normal[k]).norm() <= 1e-15 * expected);
    const double energy = 8.0 / 15.0 * table_one::e_star() * std::sqrt(r_eff[k]) * std::pow(delta[k], 2.5);
    CHECK(relative_difference(c.energy[k], energy) <= 1e-12);
    CHECK(c.couple[k].norm() == 0.0);
  }
}

TEST_CASE("hertz restitution is the set value within 2 % for any impact speed") {
  const ContactPlugins plugins;
  const double r = table_one::radius;
  const Sphere sphere{table_one::sphere_mass(r), r};
  for (double e : {0.3, 0.5, 0.9}) {
    const auto model = table_one_model(plugins, e);
    for (double v0 : {0.01, 0.1, 1.0, 5.0}) {
      CAPTURE(e);
      CAPTURE(v0);
      // 1000 steps across the elastic contact duration: the integration error is well below 2 %.
      const double t_c = table_one::hertz_contact_duration(sphere.mass / 2, r / 2, table_one::e_star(), v0);
      const CollisionResult pair = head_on_collision(*model, sphere, &sphere, v0, t_c / 1000);
      CHECK(std::abs(pair.restitution - e) <= 0.02 * e);
      CHECK(pair.steps_in_contact > 200);
      // A wall of the particles' material: same law with R* = r, m* = m.
      const double t_w = table_one::hertz_contact_duration(sphere.mass, r, table_one::e_star(), v0);
      const CollisionResult wall = head_on_collision(*model, sphere, nullptr, v0, t_w / 1000);
      CHECK(std::abs(wall.restitution - e) <= 0.02 * e);
    }
  }
}

TEST_CASE("hertz restitution holds for unequal spheres at the recommended time step") {
  const ContactPlugins plugins;
  const auto model = table_one_model(plugins, 0.5);
  const Sphere small{table_one::sphere_mass(0.35e-3), 0.35e-3};
  const Sphere large{table_one::sphere_mass(0.5e-3), 0.5e-3};
  const double dt = model->time_step_limit(small.radius, table_one::density).recommended;
  // 0.1 m/s is a fast impact for a quasi-static bending test; the contact then spans ~25 steps.
  const CollisionResult result = head_on_collision(*model, small, &large, 0.1, dt);
  MESSAGE("e = 0.5 at dt = 0.2 t_R: realised " << result.restitution << " over " << result.steps_in_contact
                                                << " steps");
  CHECK(std::abs(result.restitution - 0.5) <= 0.02 * 0.5);
}

TEST_CASE("Mindlin tangential stiffness 8 G* sqrt(R* delta) before slip") {
  const ContactPlugins plugins;
  const auto model = table_one_model(plugins);
  const double r_eff = table_one::radius / 2;
  const double delta = 0.01 * table_one::radius;
  ContactArrays c(1, model->history_size());
  c.normal[0] = Vec3::UnitZ();
  c.overlap[0] = delta;
  c.r_eff[0] = r_eff;
  c.m_eff[0] = table_one::sphere_mass(table_one::radius) / 2;
  // One step of tangential motion stretches the spring by 1e-3 delta, far below the Coulomb
  // limit (mu E* delta / (6 G*) = 0.2 delta); the next step, at rest, shows the elastic force.
  const double dt = 1e-6;
  const Vec3 shift(0.6e-3 * delta, -0.8e-3 * delta, 0.0);
  c.velocity[0] = shift / dt;
  ContactBatch moving = c.batch(dt);
  model->compute(moving);
  CHECK(c.force[0].dot(shift) < 0.0);  // resists the motion
  c.velocity[0].setZero();
  ContactBatch resting = c.batch(dt);
  model->compute(resting);
  const double stiffness = 8.0 * table_one::g_star() * std::sqrt(r_eff * delta);
  const Vec3 tangential = c.force[0] - c.force[0].z() * Vec3::UnitZ();
  CHECK((tangential + stiffness * shift).norm() <= 1e-12 * stiffness * shift.norm());
  CHECK(relative_difference(c.force[0].z(), hertz_force(r_eff, delta)) <= 1e-12);
  const double energy = 8.0 / 15.0 * table_one::e_star() * std::sqrt(r_eff) * std::pow(delta, 2.5) +
                        0.5 * stiffness * shift.squaredNorm();
  CHECK(relative_difference(c.energy[0], energy) <= 1e-12);
}

TEST_CASE("hertz Coulomb limit: a sliding contact transmits mu F_n against the sliding direction") {
  const ContactPlugins plugins;
  for (double mu : {0.1, 0.67, 2.0}) {
    CAPTURE(mu);
    const auto model = table_one_model(plugins, 0.5, mu);
    const double r_eff = table_one::radius / 2;
    const double delta = 0.01 * table_one::radius;
    ContactArrays c(1, model->history_size());
    c.normal[0] = Vec3(0.0, 0.6, 0.8);
    c.overlap[0] = delta;
    c.r_eff[0] = r_eff;
    c.m_eff[0] = table_one::sphere_mass(table_one::radius) / 2;
    // Slip starts once the spring reaches mu F_n / S_t = mu E* delta / (6 G*) <= 1.6 delta, after
    // at most 540 steps at 1e-8 m per step; 2000 steps leave it well into sliding.
    const Vec3 slide = Vec3(1.0, 0.0, 0.0) * 1e-2;  // tangential, m/s
    c.velocity[0] = slide;
    const double dt = 1e-6;
    for (int step = 0; step < 2000; ++step) {
      ContactBatch batch = c.batch(dt);
      model->compute(batch);
    }
    const double f_n = c.force[0].dot(c.normal[0]);
    CHECK(relative_difference(f_n, hertz_force(r_eff, delta)) <= 1e-12);
    const Vec3 f_t = c.force[0] - f_n * c.normal[0];
    CHECK(relative_difference(f_t.norm(), mu * f_n) <= 1e-12);
    CHECK(f_t.normalized().dot(-slide.normalized()) >= 1.0 - 1e-12);
    // The spring was reset to the cap: at rest its elastic force alone is mu F_n.
    c.velocity[0].setZero();
    ContactBatch resting = c.batch(dt);
    model->compute(resting);
    const Vec3 f_t_rest = c.force[0] - c.force[0].dot(c.normal[0]) * c.normal[0];
    CHECK(relative_difference(f_t_rest.norm(), mu * f_n) <= 1e-12);
  }
}

TEST_CASE("tangential history turns with the contact plane and keeps its length") {
  const ContactPlugins plugins;
  const auto model = table_one_model(plugins, 0.5, 10.0);
  ContactArrays c(1, model->history_size());
  REQUIRE(model->history_size() == 3);
  const double delta = 0.01 * table_one::radius;
  c.overlap[0] = delta;
  c.r_eff[0] = table_one::radius / 2;
  c.m_eff[0] = table_one::sphere_mass(table_one::radius) / 2;
  const double length = 1e-4 * delta;
  c.history = {length, 0.0, 0.0};  // stretched along x with the normal along z
  for (double angle : {0.01, 0.3, 1.2}) {
    CAPTURE(angle);
    c.history = {length, 0.0, 0.0};
    c.normal[0] = Vec3(std::sin(angle), 0.0, std::cos(angle));  // the pair turned about y
    ContactBatch batch = c.batch(1e-6);
    model->compute(batch);
    const Vec3 spring(c.history[0], c.history[1], c.history[2]);
    CHECK(relative_difference(spring.norm(), length) <= 1e-12);
    CHECK(std::abs(spring.dot(c.normal[0])) <= 1e-12 * length);
    // The same as turning the spring rigidly with the pair.
    CHECK((spring - length * Vec3(std::cos(angle), 0.0, -std::sin(angle))).norm() <= 1e-12 * length);
    const double stiffness = 8.0 * table_one::g_star() * std::sqrt(c.r_eff[0] * delta);
    const Vec3 f_t = c.force[0] - c.force[0].dot(c.normal[0]) * c.normal[0];
    CHECK((f_t + stiffness * spring).norm() <= 1e-12 * stiffness * length);
  }
}

TEST_CASE("contacts of one batch are independent: batched and one-by-one results agree exactly") {
  const ContactPlugins plugins;
  const auto model = table_one_model(plugins);
  const std::size_t n = 5;
  const std::size_t h = model->history_size();
  ContactArrays all(n, h);
  for (std::size_t k = 0; k < n; ++k) {
    const double s = double(k + 1);
    all.normal[k] = Vec3(s, 1.0, -0.5 * s).normalized();
    all.overlap[k] = 1e-6 * s;
    all.velocity[k] = Vec3(-0.01 * s, 0.02, 0.005 * s);
    all.r_eff[k] = 1e-4 * s;
    all.m_eff[k] = 1e-7 * s;
    for (std::size_t q = 0; q < h; ++q) all.history[k * h + q] = 1e-8 * s * double(q + 1);
  }
  ContactArrays copy = all;
  ContactBatch batch = all.batch(1e-6);
  model->compute(batch);
  for (std::size_t k = 0; k < n; ++k) {
    ContactArrays one(1, h);
    one.normal[0] = copy.normal[k];
    one.overlap[0] = copy.overlap[k];
    one.velocity[0] = copy.velocity[k];
    one.r_eff[0] = copy.r_eff[k];
    one.m_eff[0] = copy.m_eff[k];
    for (std::size_t q = 0; q < h; ++q) one.history[q] = copy.history[k * h + q];
    ContactBatch single = one.batch(1e-6);
    model->compute(single);
    CHECK(one.force[0] == all.force[k]);
    CHECK(one.energy[0] == all.energy[k]);
    for (std::size_t q = 0; q < h; ++q) CHECK(one.history[q] == all.history[k * h + q]);
  }
}

TEST_CASE("hertz time step: Rayleigh time of the Table I spheres, recommended 0.2 t_R") {
  const ContactPlugins plugins;
  const auto model = table_one_model(plugins);
  const TimeStepLimit limit = model->time_step_limit(table_one::radius, table_one::density);
  // t_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766), by hand:
  // pi * 0.35e-3 * sqrt(3720 / 1e7) / (0.1631 * 0.25 + 0.8766) = 2.31176e-5 s.
  const double t_rayleigh = std::numbers::pi * 0.35e-3 * std::sqrt(3720.0 / 1e7) / (0.1631 * 0.25 + 0.8766);
  CHECK(relative_difference(limit.critical, t_rayleigh) <= 1e-12);
  CHECK(relative_difference(limit.recommended, 0.2 * t_rayleigh) <= 1e-12);
  CHECK(std::abs(limit.critical - 2.31176e-5) <= 1e-10);
}
