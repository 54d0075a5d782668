// Von Mises breakage (eq. 8-10) on hand-built pairs: thresholds of each mode, tension-only
// axial stress, the combined criterion and the dominant mode; the eq. 12 time step.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "beam_setup.hpp"

using namespace shard;
using namespace shard::test;

namespace {

beam::BeamBondParams breakable() {
  beam::BeamBondParams p;  // Table I: E_b = 12.8 MPa, sigma_crit = 0.24 MPa
  p.rotational_damping = 0;
  return p;
}

const Vec3 kAxis = Vec3(1, 2, -0.5).normalized();
const Vec3 kSide = kAxis.cross(Vec3(0.2, -0.3, 1.0)).normalized();

// Deforms a fresh pair and evaluates it once.
template <class Change>
HandBonds deformed(const beam::BeamBond& model, Change&& change) {
  HandBonds w = touching_pair(kAxis);
  w.initialize(model);
  change(w);
  w.compute(model);
  return w;
}

}  // namespace

TEST_CASE("tension breaks where E_b strain reaches sigma_crit") {
  const beam::BeamBond model(breakable());
  const BeamNumbers b = numbers_of(model.params());
  const double strain_crit = model.params().critical_stress / b.E;
  for (const double f : {0.999, 1.001}) {
    HandBonds w = deformed(model, [&](HandBonds& v) { v.position[1] += f * strain_crit * b.l0 * kAxis; });
    CAPTURE(f);
    CHECK(w.broken[0] == (f > 1 ? 1 : 0));
    if (w.broken[0]) {
      CHECK(w.stress[0].tension == doctest::Approx(f * model.params().critical_stress).epsilon(1e-9));
      CHECK(w.stress[0].sigma_vm == doctest::Approx(w.stress[0].tension).epsilon(1e-9));
      CHECK(w.stress[0].dominant == BondFailureMode::Tension);
      CHECK(w.force[0].norm() == 0.0);  // a failing bond transmits nothing
    } else {
      CHECK(w.force[0].dot(kAxis) == doctest::Approx(b.axial() * f * strain_crit * b.l0).epsilon(1e-6).scale(0));
    }
  }
}

TEST_CASE("compression never breaks a bond, whatever its magnitude") {
  const beam::BeamBond model(breakable());
  const BeamNumbers b = numbers_of(model.params());
  for (const double strain : {0.01, 0.1, 0.5, 0.9}) {
    HandBonds w = deformed(model, [&](HandBonds& v) { v.position[1] -= strain * b.l0 * kAxis; });
    CAPTURE(strain);
    CHECK(w.broken[0] == 0);
    CHECK(w.force[0].dot(kAxis) == doctest::Approx(-b.axial() * strain * b.l0).epsilon(1e-9));
  }
}

TEST_CASE("bending, torsion and shear thresholds follow the von Mises combination") {
  const beam::BeamBond model(breakable());
  const BeamNumbers b = numbers_of(model.params());
  const double crit = model.params().critical_stress;

  SUBCASE("bending: E_b r_b |kappa| = sigma_crit") {
    const double angle = crit / (b.E * b.r_b) * b.l0;  // relative rotation at failure
    for (const double f : {0.999, 1.001}) {
      HandBonds w = deformed(model, [&](HandBonds& v) {
        turn(v, 0, -0.5 * f * angle * kSide);
        turn(v, 1, 0.5 * f * angle * kSide);
      });
      CAPTURE(f);
      REQUIRE(w.broken[0] == (f > 1 ? 1 : 0));
      if (f > 1) {
        CHECK(w.stress[0].bending == doctest::Approx(f * crit).epsilon(1e-9));
        CHECK(w.stress[0].dominant == BondFailureMode::Bending);
      }
    }
  }
  SUBCASE("torsion: sqrt(3) G_b r_b |kappa_twist| = sigma_crit") {
    const double angle = crit / (std::sqrt(3.0) * b.G * b.r_b) * b.l0;
    for (const double f : {0.999, 1.001}) {
      HandBonds w = deformed(model, [&](HandBonds& v) { turn(v, 1, f * angle * kAxis); });
      CAPTURE(f);
      REQUIRE(w.broken[0] == (f > 1 ? 1 : 0));
      if (f > 1) {
        CHECK(w.stress[0].torsion == doctest::Approx(f * crit / std::sqrt(3.0)).epsilon(1e-9));
        CHECK(w.stress[0].dominant == BondFailureMode::Torsion);
      }
    }
  }
  SUBCASE("shear: sqrt(3) G_b |Gamma_shear| = sigma_crit") {
    const double offset = crit / (std::sqrt(3.0) * b.G) * b.l0;
    for (const double f : {0.999, 1.001}) {
      HandBonds w = deformed(model, [&](HandBonds& v) { v.position[1] += f * offset * kSide; });
      CAPTURE(f);
      REQUIRE(w.broken[0] == (f > 1 ? 1 : 0));
      if (f > 1) CHECK(w.stress[0].dominant == BondFailureMode::Shear);
    }
  }
  SUBCASE("tension plus torsion: sqrt(sigma^2 + 3 tau^2) with half the critical tension") {
    // sigma = crit/2 needs tau = crit/2 for sigma_vm = crit: sqrt(1/4 + 3/4) = 1.
    const double strain = 0.5 * crit / b.E;
    const double angle = 0.5 * crit / (b.G * b.r_b) * b.l0;
    for (const double f : {0.999, 1.001}) {
      HandBonds w = deformed(model, [&](HandBonds& v) {
        v.position[1] += strain * b.l0 * kAxis;
        turn(v, 1, f * angle * kAxis);
      });
      CAPTURE(f);
      REQUIRE(w.broken[0] == (f > 1 ? 1 : 0));
      if (f > 1) {
        CHECK(w.stress[0].tension == doctest::Approx(0.5 * crit).epsilon(1e-6));
        CHECK(w.stress[0].torsion == doctest::Approx(0.5 * f * crit).epsilon(1e-6));
        CHECK(w.stress[0].sigma_vm == doctest::Approx(std::sqrt(0.25 + 0.75 * f * f) * crit).epsilon(1e-6));
        CHECK(w.stress[0].dominant == BondFailureMode::Torsion);  // sqrt(3) tau > sigma
      }
    }
  }
  SUBCASE("compression does not relieve bending: the tensile fibre still fails") {
    const double angle = crit / (b.E * b.r_b) * b.l0;
    HandBonds w = deformed(model, [&](HandBonds& v) {
      v.position[1] -= 0.05 * b.l0 * kAxis;
      turn(v, 0, -0.5 * 1.001 * angle * kSide);
      turn(v, 1, 0.5 * 1.001 * angle * kSide);
    });
    CHECK(w.broken[0] == 1);
    CHECK(w.stress[0].tension == 0.0);
    CHECK(w.stress[0].dominant == BondFailureMode::Bending);
  }
}

TEST_CASE("breakage = false keeps every bond") {
  beam::BeamBondParams p = breakable();
  p.breakage = false;
  const beam::BeamBond model(p);
  const BeamNumbers b = numbers_of(p);
  HandBonds w = deformed(model, [&](HandBonds& v) { v.position[1] += 0.5 * b.l0 * kAxis; });
  CHECK(w.broken[0] == 0);
  CHECK(w.force[0].dot(kAxis) == doctest::Approx(b.axial() * 0.5 * b.l0).epsilon(1e-9));
}

TEST_CASE("eq. 12 time step for Table I: t_bond = 0.17 sqrt(m / K) ~ 1.7e-6 s") {
  const beam::BeamBond model(breakable());
  HandBonds w = touching_pair();
  w.initialize(model);
  BondBatch batch = w.batch(model);
  const TimeStepLimit limit = model.time_step_limit(batch);
  // By hand: m = 3720 * 4/3 pi (0.35e-3)^3 = 6.681e-7 kg; K = 12.8e6 * pi (0.35e-3)^2 / 0.7e-3
  // = 7037 N/m; 0.17 sqrt(6.681e-7 / 7037) = 1.656e-6 s.
  CHECK(limit.critical == doctest::Approx(1.656e-6).epsilon(1e-3).scale(0));
  CHECK(limit.recommended == limit.critical);
}

TEST_CASE("eq. 4's dashpot shrinks the step by 1 / (sqrt(1 + z^2) + z), z = (c / K) / t_bond") {
  // bar_pull's damping of 0.3 N s/m blew up at the undamped step (docs/explanation/physics.md); with the
  // damped step it runs, as does 1.0.
  auto p = breakable();
  const beam::BeamBond elastic(p);
  HandBonds a = touching_pair();
  a.initialize(elastic);
  BondBatch ba = a.batch(elastic);
  const double t0 = elastic.time_step_limit(ba).critical;
  const double K = 7037.0;  // N/m, as above
  for (const double c : {1e-3, 0.1, 1.0}) {
    p.damping = c;
    const beam::BeamBond damped(p);
    HandBonds b = touching_pair();
    b.initialize(damped);
    BondBatch bb = b.batch(damped);
    const double z = c / K / t0;
    CHECK(damped.time_step_limit(bb).critical / t0 == doctest::Approx(1 / (std::sqrt(1 + z * z) + z)).epsilon(1e-3).scale(0));
  }
}

TEST_CASE("eq. 12 takes the lightest particle and the stiffest bond, the dashpot the softest bond") {
  // Two bonds of different sizes: 0.35 mm spheres (K = 7037 N/m, m = 6.681e-7 kg) and 0.5 mm
  // spheres (K = 12.8e6 pi (0.5e-3)^2 / 1e-3 = 10053 N/m). The step pairs the small spheres' mass
  // with the big bond's stiffness; eq. 4's tau = c / K comes from the small, softer bond. Two
  // fields of one bond each would give neither.
  auto p = breakable();
  p.damping = 0.3;  // N s/m, bar_pull's
  const beam::BeamBond model(p);
  HandBonds w;
  const Index a = w.add_sphere(Vec3(0, 0, 0), 0.35e-3), b = w.add_sphere(Vec3(0.7e-3, 0, 0), 0.35e-3);
  const Index c = w.add_sphere(Vec3(0, 5e-3, 0), 0.5e-3), d = w.add_sphere(Vec3(1e-3, 5e-3, 0), 0.5e-3);
  w.add_bond(a, b);
  w.add_bond(c, d);
  w.initialize(model);
  BondBatch batch = w.batch(model);
  const double m_light = 3720 * 4.0 / 3.0 * std::numbers::pi * std::pow(0.35e-3, 3);
  const double K_stiff = 12.8e6 * std::numbers::pi * 0.25e-6 / 1e-3, K_soft = 12.8e6 * std::numbers::pi * 0.1225e-6 / 0.7e-3;
  const double t = 0.17 * std::sqrt(m_light / K_stiff);
  const double z = p.damping / K_soft / t;
  CHECK(model.time_step_limit(batch).critical == doctest::Approx(t / (std::sqrt(1 + z * z) + z)).epsilon(1e-12).scale(0));
}
