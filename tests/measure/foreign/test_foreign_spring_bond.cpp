// The foreign spring bond's law (foreign_spring_bond.hpp): linear springs on the bond-frame
// motion, no load for a rigid motion, breakage where the force criterion reaches 1.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "../../bond/random_bonds.hpp"
#include "spring_pair.hpp"

namespace shard::foreign_test {

using foreign::SpringBond;

TEST_CASE("foreign spring bond: pure axial stretch and compression give F = k_n dx") {
  const auto p = undamped();
  const SpringBond model(p);
  SpringPair pair(model);
  for (double dx : {1e-7, 1e-6, 2e-5, -1e-6, -3e-5}) {
    pair.place(dx);
    pair.compute(model);
    REQUIRE_FALSE(pair.broken());
    // r - r0 is one rounding of (r0 + dx) - r0: relative 1e-16 of r0 / dx <= 1.7e-9 at dx = 1e-7.
    CHECK(pair.force_on_first().x() == doctest::Approx(p.normal_stiffness * dx).epsilon(1e-8).scale(0));
    CHECK(pair.force_on_first().y() == 0);
    CHECK(pair.force_on_first().z() == 0);
    CHECK(pair.scene.torque_i[0].norm() == 0);
    CHECK(pair.scene.torque_j[0].norm() == 0);
    CHECK(pair.scene.energy[0] == doctest::Approx(0.5 * p.normal_stiffness * dx * dx).epsilon(1e-8).scale(0));
  }
}

TEST_CASE("foreign spring bond: a rigid motion of bonded pairs gives no load") {
  foreign::SpringBondParams p;  // damping on: the velocity terms must vanish too
  const SpringBond model(p);
  auto s = test::random_pairs<test::HandBonds>(500, 11);
  s.initialize(model);
  std::mt19937_64 rng(5);
  const Quat turn = test::random_rotation(rng, 3.0);
  const Vec3 centre(3e-3, -2e-3, 1e-3), drift(0.01, -0.02, 0.03), spin(4.0, -7.0, 2.0);
  for (std::size_t k = 0; k < s.position.size(); ++k) {
    s.position[k] = centre + turn * (s.position[k] - centre) + Vec3(1e-3, 2e-3, -1e-3);
    s.orientation[k] = (turn * s.orientation[k]).normalized();
    s.velocity[k] = drift + spin.cross(s.position[k]);
    s.omega[k] = spin;
  }
  s.compute(model);
  // Scale: a 1 um stretch loads a bond with 1.5e-2 N; rounding of positions ~1e-2 m leaves
  // ~1e-17 m, i.e. ~1e-13 N, and ~1e-15 rad of relative rotation, ~1e-17 N m.
  double largest_force = 0, largest_torque = 0;
  for (std::size_t k = 0; k < s.i.size(); ++k) {
    REQUIRE(s.broken[k] == 0);
    largest_force = std::max(largest_force, s.force[k].norm());
    largest_torque = std::max({largest_torque, s.torque_i[k].norm(), s.torque_j[k].norm()});
  }
  MESSAGE("largest force ", largest_force, " N, torque ", largest_torque, " N m");
  CHECK(largest_force < 1e-10);
  CHECK(largest_torque < 1e-13);
}

TEST_CASE("foreign spring bond: loads conserve momentum and angular momentum") {
  const SpringBond model(foreign::SpringBondParams{});
  auto s = test::random_pairs<test::HandBonds>(300, 3);
  s.initialize(model);
  test::deform(s, 9, 0.05, 3.0);
  s.compute(model);
  for (std::size_t k = 0; k < s.i.size(); ++k) {
    if (s.broken[k]) continue;
    const Vec3 xi = s.position[static_cast<std::size_t>(s.i[k])], xj = s.position[static_cast<std::size_t>(s.j[k])];
    // Force f on i, -f on j: the torques must balance the couple (xi - xj) x f.
    const Vec3 total = (xi - xj).cross(s.force[k]) + s.torque_i[k] + s.torque_j[k];
    // Rounding: ~1e-16 of the largest term; 1e-12 leaves room for the cancellation.
    const double scale = s.force[k].norm() * (xi - xj).norm() + s.torque_i[k].norm() + s.torque_j[k].norm();
    CHECK(total.norm() <= 1e-12 * scale);
  }
}

// Steps a load path t = 1..n and returns the first step at which the bond broke (0: never).
template <class Place>
int break_step(const SpringBond& model, SpringPair& pair, int n, Place place) {
  for (int t = 1; t <= n; ++t) {
    place(t);
    pair.compute(model);
    if (pair.broken()) return t;
  }
  return 0;
}

TEST_CASE("foreign spring bond: breaks where the force criterion reaches 1") {
  const auto p = undamped();
  const SpringBond model(p);
  const double k_n = p.normal_stiffness, k_s = p.shear_stiffness, r0 = SpringPair::rest;
  const int n = 4000;

  SUBCASE("tension: at k_n dx = F_n,c") {
    SpringPair pair(model);
    const double h = 2 * p.normal_strength / k_n / n;
    const int t = break_step(model, pair, n, [&](int s) { pair.place(s * h); });
    REQUIRE(t > 0);
    CHECK(k_n * (t - 1) * h < p.normal_strength);
    CHECK(k_n * t * h >= p.normal_strength);
  }
  SUBCASE("a bond between two spheres of an unbreakable zone holds, and still pulls") {
    SpringPair pair(model);
    pair.scene.flags = {kUnbreakable, kUnbreakable};
    const double dx = 3 * p.normal_strength / k_n;
    CHECK(break_step(model, pair, n, [&](int s) { pair.place(s * dx / n); }) == 0);
    CHECK(pair.force_on_first().x() == doctest::Approx(p.normal_stiffness * dx).epsilon(1e-8));
  }
  SUBCASE("one end in a zone is not enough") {
    SpringPair pair(model);
    pair.scene.flags = {kUnbreakable, 0};
    CHECK(break_step(model, pair, n, [&](int s) { pair.place(s * 2 * p.normal_strength / k_n / n); }) > 0);
  }
  SUBCASE("compression never breaks a bond") {
    SpringPair pair(model);
    const double h = -5 * p.normal_strength / k_n / n;
    CHECK(break_step(model, pair, n, [&](int s) { pair.place(s * h); }) == 0);
  }
  SUBCASE("tension and shear together: (F_n / F_n,c)^2 + (F_s / F_s,c)^2 = 1") {
    SpringPair pair(model);
    // The second sphere moves along (1, 2): r = |(r0 + dx, dy)|, stretch r - r0, and the shear
    // offset of a bond whose particles did not turn is r0 |dy| / r (spring_kinematics.hpp).
    const double h = 1e-4 / n;
    auto criterion = [&](int s) {
      const double dx = s * h, dy = 2 * s * h, r = std::hypot(r0 + dx, dy);
      const double fn = k_n * (r - r0), fs = k_s * r0 * dy / r;
      return std::pow(fn / p.normal_strength, 2) + std::pow(fs / p.shear_strength, 2);
    };
    const int t = break_step(model, pair, n, [&](int s) { pair.place(s * h, 2 * s * h); });
    REQUIRE(t > 1);
    CHECK(criterion(t - 1) < 1);
    CHECK(criterion(t) >= 1);
    // Both terms matter at the break (neither is below a tenth of the criterion).
    const double dx = t * h, dy = 2 * t * h, r = std::hypot(r0 + dx, dy);
    CHECK(std::pow(k_n * (r - r0) / p.normal_strength, 2) > 0.1);
    CHECK(std::pow(k_s * r0 * dy / r / p.shear_strength, 2) > 0.1);
  }
  SUBCASE("bending: the spheres turned by -phi and +phi about z, at 2 phi k_b = T_b,c") {
    SpringPair pair(model);
    const double h = 2 * p.bending_strength / p.bending_stiffness / n;
    const auto turn = [](double a) { return Quat(Eigen::AngleAxisd(a, Vec3::UnitZ())); };
    const int t = break_step(model, pair, n, [&](int s) { pair.place(0, 0, turn(-0.5 * s * h), turn(0.5 * s * h)); });
    REQUIRE(t > 0);
    // The rotation vector of the relative turn is exact to ~1e-16 rad against h ~ 6e-5 rad.
    CHECK(p.bending_stiffness * (t - 1) * h < p.bending_strength);
    CHECK(p.bending_stiffness * t * h >= p.bending_strength * (1 - 1e-12));
    CHECK(pair.scene.stress[0].dominant == BondFailureMode::Bending);
  }
  SUBCASE("twisting: turned about the bond axis, at phi k_t = T_t,c") {
    SpringPair pair(model);
    const double h = 2 * p.twisting_strength / p.twisting_stiffness / n;
    const int t = break_step(model, pair, n, [&](int s) {
      pair.place(0, 0, Quat::Identity(), Quat(Eigen::AngleAxisd(s * h, Vec3::UnitX())));
    });
    REQUIRE(t > 0);
    CHECK(p.twisting_stiffness * (t - 1) * h < p.twisting_strength);
    CHECK(p.twisting_stiffness * t * h >= p.twisting_strength * (1 - 1e-12));
    CHECK(pair.scene.stress[0].dominant == BondFailureMode::Torsion);
  }
}

TEST_CASE("foreign spring bond: bending and twisting springs, shear by translation") {
  const auto p = undamped();
  const SpringBond model(p);
  SpringPair pair(model);
  const double phi = 1e-3;
  pair.place(0, 0, Quat::Identity(), Quat(Eigen::AngleAxisd(phi, Vec3::UnitX())));
  pair.compute(model);
  // Twist of the second sphere by phi: torque -k_t phi on it, +k_t phi on the first.
  CHECK(pair.scene.torque_j[0].x() == doctest::Approx(-p.twisting_stiffness * phi).epsilon(1e-9).scale(0));
  CHECK(pair.scene.torque_i[0].x() == doctest::Approx(p.twisting_stiffness * phi).epsilon(1e-9).scale(0));
  CHECK(pair.force_on_first().norm() < 1e-12);

  // A small sideways offset dy without turning the spheres: shear force k_s dy on the first
  // towards +y (to second order in dy / r0) and the couple split equally as torques.
  const double dy = 1e-7;
  pair.place(0, dy);
  pair.compute(model);
  CHECK(pair.force_on_first().y() == doctest::Approx(p.shear_stiffness * dy).epsilon(1e-6).scale(0));
  CHECK(pair.scene.torque_i[0].z() == doctest::Approx(0.5 * SpringPair::rest * p.shear_stiffness * dy).epsilon(1e-6).scale(0));
  CHECK(pair.scene.torque_j[0].z() == doctest::Approx(pair.scene.torque_i[0].z()).epsilon(1e-12).scale(0));
}

TEST_CASE("foreign spring bond: the stable step is 0.17 sqrt(m / k) of the stiffest spring") {
  auto p = undamped();
  const SpringBond plain(p);
  SpringPair pair(plain);
  const double m = pair.scene.mass[0];
  BondBatch b = pair.scene.batch(plain);
  const double translational = 0.17 * std::sqrt(m / p.normal_stiffness);
  CHECK(plain.time_step_limit(b).recommended <= translational * (1 + 1e-12));
  p.compression_ratio = 4;
  p.bending_stiffness = p.twisting_stiffness = 1e-9;  // the normal spring sets the step
  p.shear_stiffness = 1e-3;
  const SpringBond stiff(p);
  CHECK(stiff.time_step_limit(b).recommended == doctest::Approx(translational / 2).epsilon(1e-12));
}

}  // namespace shard::foreign_test
