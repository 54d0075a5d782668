// The beam bond evaluated directly on hand-built pairs: rigid-motion invariance, the four
// small-strain stiffnesses, exact consistency of forces and torques with the stored energy,
// angular-momentum balance and order independence.
#include <doctest/doctest.h>

#include <random>

#include "beam_setup.hpp"

using namespace shard;
using namespace shard::test;

namespace {

beam::BeamBondParams undamped() {
  beam::BeamBondParams p;
  p.rotational_damping = 0;
  p.breakage = false;
  return p;
}

Vec3 some_perpendicular(const Vec3& n) { return n.cross(Vec3(0.2, -0.3, 1.0)).normalized(); }

}  // namespace

TEST_CASE("rigid translation and rotation of a bonded pair give no force and no torque") {
  const beam::BeamBond model(undamped());
  const BeamNumbers b = numbers_of(model.params());
  const double force_1pc = b.E * b.A * 0.01;             // axial force at 1 % strain
  const double torque_1pc = b.E * b.J * 0.01 / b.l0;     // bending moment at 1 % curvature l0

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const double degrees : {1.0, 30.0, 60.0, 90.0}) {
    for (int trial = 0; trial < 5; ++trial) {
      HandBonds w = touching_pair();
      w.initialize(model);
      const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
      const Quat turn_q = rotation(axis * degrees * std::numbers::pi / 180);
      const Vec3 pivot(u(rng) * 1e-3, u(rng) * 1e-3, u(rng) * 1e-3);
      const Vec3 shift(u(rng) * 1e-2, u(rng) * 1e-2, u(rng) * 1e-2);
      for (Index k = 0; k < 2; ++k) {
        w.position[k] = turn_q * (w.position[k] - pivot) + pivot + shift;
        w.orientation[k] = (turn_q * w.orientation[k]).normalized();
      }
      w.compute(model);
      CAPTURE(degrees);
      CHECK(w.force[0].norm() < 1e-9 * force_1pc);
      CHECK(w.torque_i[0].norm() < 1e-9 * torque_1pc);
      CHECK(w.torque_j[0].norm() < 1e-9 * torque_1pc);
      CHECK(w.energy[0] < 1e-15 * 0.5 * force_1pc * 0.01 * b.l0);
    }
  }
}

TEST_CASE("a deformed pair turned rigidly carries its forces with it (objectivity)") {
  const beam::BeamBond model(undamped());
  HandBonds w = touching_pair();
  w.initialize(model);
  w.position[1] += Vec3(2e-6, -3e-6, 1e-6);
  turn(w, 0, Vec3(0.01, 0.02, -0.005));
  turn(w, 1, Vec3(-0.01, 0.004, 0.02));
  w.compute(model);
  const Vec3 f = w.force[0], ti = w.torque_i[0], tj = w.torque_j[0];
  const double e = w.energy[0];

  const Quat q = rotation(Vec3(0.9, -0.4, 1.2));
  for (Index k = 0; k < 2; ++k) {
    w.position[k] = q * w.position[k];
    w.orientation[k] = (q * w.orientation[k]).normalized();
  }
  w.compute(model);
  CHECK((w.force[0] - q * f).norm() < 1e-10 * f.norm());
  CHECK((w.torque_i[0] - q * ti).norm() < 1e-10 * ti.norm());
  CHECK((w.torque_j[0] - q * tj).norm() < 1e-10 * tj.norm());
  CHECK(w.energy[0] == doctest::Approx(e).epsilon(1e-10).scale(0));
}

TEST_CASE("small-strain stiffness of each mode matches the beam's section stiffness") {
  const beam::BeamBond model(undamped());
  const BeamNumbers b = numbers_of(model.params());
  const double eps = 1e-6;  // second-order terms are eps times smaller
  const Vec3 n = Vec3(1, 2, -0.5).normalized();
  const Vec3 e = some_perpendicular(n);
  // Torques of order 1e-12 of the 1 % value are rounding noise of the positions (|x| >> l0).
  const double roundoff_torque = b.E * b.J * 0.01 / b.l0;

  SUBCASE("axial: E_b A_b / l0") {
    HandBonds w = touching_pair();
    w.initialize(model);
    w.position[1] += eps * b.l0 * n;
    w.compute(model);
    CHECK(w.force[0].dot(n) / (eps * b.l0) == doctest::Approx(b.axial()).epsilon(1e-5));
    CHECK(w.force[0].cross(n).norm() < 1e-9 * w.force[0].norm());
    CHECK(w.energy[0] == doctest::Approx(0.5 * b.axial() * std::pow(eps * b.l0, 2)).epsilon(1e-5).scale(0));
  }
  SUBCASE("shear: a_s G_b A_b / l0, with the balancing couple split equally") {
    HandBonds w = touching_pair();
    w.initialize(model);
    w.position[1] += eps * b.l0 * e;
    w.compute(model);
    const Vec3 f = w.force[0];
    CHECK(f.dot(e) / (eps * b.l0) == doctest::Approx(b.shear()).epsilon(1e-5));
    const Vec3 half_couple = 0.5 * (w.position[1] - w.position[0]).cross(f);
    CHECK((w.torque_i[0] - half_couple).norm() < 1e-5 * half_couple.norm());
    CHECK((w.torque_j[0] - half_couple).norm() < 1e-5 * half_couple.norm());
  }
  SUBCASE("twist: 2 G_b J_b / l0") {
    HandBonds w = touching_pair();
    w.initialize(model);
    turn(w, 1, eps * n);
    w.compute(model);
    CHECK(w.torque_i[0].dot(n) / eps == doctest::Approx(b.twist()).epsilon(1e-5).scale(0));
    CHECK((w.torque_j[0] + w.torque_i[0]).norm() < 1e-12 * roundoff_torque);
    CHECK(w.force[0].norm() < 1e-9 * b.axial() * eps * b.l0);
  }
  SUBCASE("bending: E_b J_b / l0 (opposite end rotations, no shear)") {
    HandBonds w = touching_pair();
    w.initialize(model);
    turn(w, 0, -0.5 * eps * e);
    turn(w, 1, 0.5 * eps * e);
    w.compute(model);
    CHECK(w.torque_i[0].dot(e) / eps == doctest::Approx(b.bending()).epsilon(1e-5).scale(0));
    CHECK((w.torque_j[0] + w.torque_i[0]).norm() < 1e-12 * roundoff_torque);
    CHECK(w.force[0].norm() < 1e-9 * b.axial() * eps * b.l0);
  }
}

// Central differences of the bond energy against the returned forces and torques: exact
// agreement means an undamped bond is conservative.
TEST_CASE("forces and torques are the exact derivatives of the bond energy") {
  const beam::BeamBond model(undamped());
  const BeamNumbers b = numbers_of(model.params());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 8; ++trial) {
    HandBonds w = touching_pair(Vec3(u(rng), u(rng), u(rng)));
    w.initialize(model);
    // A mixed deformation of about 1 % strain and 0.02 rad, then a large rigid turn.
    w.position[1] += 0.01 * b.l0 * Vec3(u(rng), u(rng), u(rng));
    turn(w, 0, 0.02 * Vec3(u(rng), u(rng), u(rng)));
    turn(w, 1, 0.02 * Vec3(u(rng), u(rng), u(rng)));
    const Quat big = rotation(Vec3(u(rng), u(rng), u(rng)) * 2.0);
    for (Index k = 0; k < 2; ++k) {
      w.position[k] = big * w.position[k];
      w.orientation[k] = (big * w.orientation[k]).normalized();
    }
    w.compute(model);
    const Vec3 force_i = w.force[0];
    const Vec3 torque[2] = {w.torque_i[0], w.torque_j[0]};

    const double hx = 1e-7 * b.l0, hr = 1e-7;
    auto energy_after = [&](auto&& change) {
      HandBonds v = w;
      change(v);
      v.compute(model);
      return v.energy[0];
    };
    for (int c = 0; c < 3; ++c) {
      const Vec3 dx = hx * Vec3::Unit(c);
      const double fd_force_i = -(energy_after([&](HandBonds& v) { v.position[0] += dx; }) -
                                  energy_after([&](HandBonds& v) { v.position[0] -= dx; })) / (2 * hx);
      const double fd_force_j = -(energy_after([&](HandBonds& v) { v.position[1] += dx; }) -
                                  energy_after([&](HandBonds& v) { v.position[1] -= dx; })) / (2 * hx);
      CHECK(fd_force_i == doctest::Approx(force_i[c]).scale(force_i.norm()).epsilon(1e-6));
      CHECK(fd_force_j == doctest::Approx(-force_i[c]).scale(force_i.norm()).epsilon(1e-6));
      for (Index k = 0; k < 2; ++k) {
        const Vec3 dphi = hr * Vec3::Unit(c);
        const double fd_torque = -(energy_after([&](HandBonds& v) { turn(v, k, dphi); }) -
                                   energy_after([&](HandBonds& v) { turn(v, k, -dphi); })) / (2 * hr);
        CHECK(fd_torque == doctest::Approx(torque[k][c]).scale(torque[k].norm()).epsilon(1e-6));
      }
    }
    // Balance of angular momentum about any point: torques plus the moment of the force pair.
    const Vec3 net = torque[0] + torque[1] + (w.position[0] - w.position[1]).cross(force_i);
    CHECK(net.norm() < 1e-12 * (torque[0].norm() + force_i.norm() * b.l0));
  }
}

TEST_CASE("listing a bond the other way round gives the same physics") {
  const beam::BeamBond model(undamped());
  HandBonds a = touching_pair();
  a.position[1] += Vec3(3e-6, -1e-6, 2e-6);  // not in the reference state yet
  a.initialize(model);
  a.position[1] += Vec3(2e-6, 1e-6, -4e-6);
  turn(a, 0, Vec3(0.01, -0.02, 0.015));
  turn(a, 1, Vec3(-0.03, 0.01, 0.02));

  SUBCASE("bond (j, i): identical arithmetic, bitwise equal") {
    HandBonds s = a;
    std::swap(s.i[0], s.j[0]);
    s.initialize(model);
    s.state = a.state;
    a.compute(model);
    s.compute(model);
    CHECK(s.force[0] == -a.force[0]);
    CHECK(s.torque_i[0] == a.torque_j[0]);
    CHECK(s.torque_j[0] == a.torque_i[0]);
    CHECK(s.energy[0] == a.energy[0]);
  }
  SUBCASE("stable ids reversed: the other particle leads, the mirrored frame gives the same result") {
    HandBonds ref = touching_pair();
    ref.position[1] += Vec3(3e-6, -1e-6, 2e-6);
    ref.initialize(model);
    HandBonds s = ref;
    std::swap(s.id[0], s.id[1]);
    s.initialize(model);  // records the reference with particle 1 as the bond's first end
    for (HandBonds* w : {&ref, &s}) {
      w->position[1] += Vec3(2e-6, 1e-6, -4e-6);
      turn(*w, 0, Vec3(0.01, -0.02, 0.015));
      turn(*w, 1, Vec3(-0.03, 0.01, 0.02));
      w->compute(model);
    }
    const double f = ref.force[0].norm(), t = ref.torque_i[0].norm() + ref.torque_j[0].norm();
    CHECK((s.force[0] - ref.force[0]).norm() < 1e-11 * f);
    CHECK((s.torque_i[0] - ref.torque_i[0]).norm() < 1e-11 * t);
    CHECK((s.torque_j[0] - ref.torque_j[0]).norm() < 1e-11 * t);
    CHECK(s.energy[0] == doctest::Approx(ref.energy[0]).epsilon(1e-11).scale(0));
  }
}
