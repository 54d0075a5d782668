// Kelvin-Voigt rate dependence: at the same strain the force of a bond stretched at two rates
// differs by eta A_b (rate2 - rate1), eta = E_b tau_v; the strength criterion sees the viscous
// stress, so a fast pull breaks the bond at a smaller strain.
#include <doctest/doctest.h>

#include <cmath>

#include "beam_plus_setup.hpp"

namespace shard::effects_test {

TEST_CASE("viscous bond: force difference between two strain rates is eta A rate difference") {
  auto p = table_one_plus();
  p.viscosity_time = 2e-4;  // s
  const beam_plus::BeamBondPlus model(p);
  Pair pair(model);
  const double E = p.base.youngs_modulus, A = Pair::area, l0 = Pair::l0;
  const double eta = E * p.viscosity_time;
  const double eps = 5e-3;
  const double v1 = 0.002, v2 = 0.02;  // m/s: strain rates v / l0 = 2.9 and 29 1/s
  pair.set(eps, Vec3(v1, 0, 0));
  const double f1 = pair.axial_force(model);
  pair.set(eps, Vec3(v2, 0, 0));
  const double f2 = pair.axial_force(model);
  pair.set(eps);
  const double f0 = pair.axial_force(model);
  CHECK(f0 == doctest::Approx(E * A * eps).epsilon(1e-10));
  CHECK(f2 - f1 == doctest::Approx(eta * A * (v2 - v1) / l0).epsilon(1e-9));
  CHECK(f1 - f0 == doctest::Approx(eta * A * v1 / l0).epsilon(1e-9));
  // Stored energy is the elastic part only.
  CHECK(pair.scene.energy[0] == doctest::Approx(0.5 * E * A * l0 * eps * eps).epsilon(1e-10));

  // Shear: a transverse velocity adds a_s G_b tau_v A_b v_t / l0 on the shear force.
  const double G = p.base.effective_shear_modulus();
  pair.set(0, Vec3(0, v2, 0));
  pair.axial_force(model);
  CHECK(pair.scene.force[0].y() == doctest::Approx(p.base.shear_coefficient * G * p.viscosity_time * A * v2 / l0).epsilon(1e-9));
}

TEST_CASE("viscous bond: the breakage criterion sees E_b (eps + tau_v d eps/dt)") {
  auto p = table_one_plus();
  p.viscosity_time = 2e-4;
  const beam_plus::BeamBondPlus model(p);
  Pair pair(model);
  const double E = p.base.youngs_modulus, sc = p.base.critical_stress, l0 = Pair::l0;
  const double eps = 0.9 * sc / E;   // 10 % below the static strength
  const double rate = 0.2 * sc / E / p.viscosity_time;  // tau_v rate = 20 % of eps0
  pair.set(eps);
  pair.axial_force(model);
  CHECK_FALSE(pair.broken());
  pair.set(eps, Vec3(rate * l0, 0, 0));
  pair.axial_force(model);
  CHECK(pair.broken());
  CHECK(pair.scene.stress[0].sigma_vm == doctest::Approx(1.1 * sc).epsilon(1e-9));
}

TEST_CASE("viscous bond: the stable step shrinks by sqrt(1 + z^2) - z") {
  auto p = table_one_plus();
  const beam_plus::BeamBondPlus elastic(p);
  p.viscosity_time = 2e-6;
  const beam_plus::BeamBondPlus viscous(p);
  Pair a(elastic), b(viscous);
  const double t0 = elastic.time_step_limit(a.scene.batch(elastic)).critical;
  const double t1 = viscous.time_step_limit(b.scene.batch(viscous)).critical;
  const double k = p.base.youngs_modulus * Pair::area / Pair::l0;
  const double z = 0.5 * p.viscosity_time * std::sqrt(k / a.scene.mass[0]);
  CHECK(t1 / t0 == doctest::Approx(std::sqrt(1 + z * z) - z).epsilon(1e-12));
  CHECK(t1 < t0);
}

}  // namespace shard::effects_test
