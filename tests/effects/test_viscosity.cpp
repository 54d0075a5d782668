// Rate dependence as a standard linear solid (maxwell_arm.hpp): the elastic beam E_b beside a
// Maxwell arm (spring beta E_b, dashpot eta = E_b tau_v, relaxation time tau_r = tau_v / beta).
// Pulled at a constant strain rate r from rest, the arm strain is exactly
//   h(t) = tau_v r (1 - exp(-t / tau_r)),
// so the force tends to the Kelvin-Voigt E_b A_b (eps + tau_v r); held, h relaxes as exp(-t / tau_r);
// a jump fast against tau_r meets (1 + beta) E_b. The strength check sees eps + h.
#include <doctest/doctest.h>

#include <cmath>

#include "beam_effects_setup.hpp"

namespace shard::effects_test {
namespace {

constexpr double kTau = 2e-4;  // s, tau_v
constexpr double kBeta = 1.0;  // tau_r = 2e-4 s

beam::BeamBondParams viscous_params(double beta = kBeta) {
  auto p = table_one_params();
  p.effects.viscosity_time = kTau;
  p.effects.viscous_modulus_ratio = beta;
  return p;
}

// Moves the pair from strain eps_from to eps_to in `steps` steps of the scene's dt, linearly in
// time, and returns the axial force after the last one.
double ramp(Pair& pair, const BondModel& model, double eps_from, double eps_to, int steps) {
  const double v = (eps_to - eps_from) * Pair::l0 / (steps * pair.scene.dt);
  double f = 0;
  for (int n = 1; n <= steps; ++n) {
    pair.set(eps_from + (eps_to - eps_from) * n / steps, Vec3(v, 0, 0));
    f = pair.axial_force(model);
  }
  return f;
}

}  // namespace

TEST_CASE("viscous bond: a constant-rate pull follows E_b A_b (eps + tau_v r (1 - exp(-t / tau_r)))") {
  const auto p = viscous_params();
  const beam::BeamBond model(p);
  Pair pair(model);
  const double E = p.youngs_modulus, A = Pair::area, dt = pair.scene.dt;
  const double tau_r = kTau / kBeta;
  const double rate = 5.0;  // 1/s: eps = 5e-3 after 1 ms, stress ~1/4 of sigma_crit
  double eps = 0, f = 0;
  for (const int steps : {100, 900}) {  // to t = tau_r / 2, then to 5 tau_r
    const double next = eps + rate * steps * dt;
    f = ramp(pair, model, eps, next, steps);
    eps = next;
    const double t = eps / rate;
    const double h = kTau * rate * (1 - std::exp(-t / tau_r));
    CHECK(f == doctest::Approx(E * A * (eps + h)).epsilon(1e-9));
    // Stored energy: the beam's and the arm spring's, h / beta of strain.
    CHECK(pair.scene.energy[0] ==
          doctest::Approx(0.5 * E * A * Pair::l0 * (eps * eps + h * h / kBeta)).epsilon(1e-9).scale(0));
  }
  // After 5 tau_r the arm is within exp(-5) = 0.7 % of the Kelvin-Voigt stress E_b tau_v r.
  const double viscous = f - E * A * eps;
  CHECK(viscous == doctest::Approx(E * A * kTau * rate).epsilon(0.0068).scale(0));
  CHECK(viscous < E * A * kTau * rate);

  SUBCASE("held at constant strain, the arm relaxes as exp(-t / tau_r)") {
    const double h0 = kTau * rate * (1 - std::exp(-5.0));
    const int steps = 100;  // tau_r / 2
    const double held = ramp(pair, model, eps, eps, steps);
    CHECK(held - E * A * eps == doctest::Approx(E * A * h0 * std::exp(-steps * dt / tau_r)).epsilon(1e-9));
  }
}

TEST_CASE("viscous bond: a jump fast against tau_r meets (1 + beta) E_b, slow loading only E_b") {
  for (const double beta : {0.5, 1.0, 4.0}) {
    const auto p = viscous_params(beta);
    const beam::BeamBond model(p);
    Pair pair(model);
    const double E = p.youngs_modulus, A = Pair::area;
    const double eps = 1e-3;
    const double x = pair.scene.dt * beta / kTau;  // dt / tau_r
    const double gain = beta * (1 - std::exp(-x)) / x;
    pair.set(eps);
    CHECK(pair.axial_force(model) == doctest::Approx(E * A * eps * (1 + gain)).epsilon(1e-10));
    CHECK(gain == doctest::Approx(beta).epsilon(0.01).scale(0));
  }
  // The same strain reached over 50 tau_r: the arm stress is tau_v r of strain, 2 % of eps.
  const auto p = viscous_params();
  const beam::BeamBond model(p);
  Pair pair(model);
  const double E = p.youngs_modulus, A = Pair::area;
  const double f = ramp(pair, model, 0, 1e-3, 10000);
  CHECK(f == doctest::Approx(E * A * 1e-3 * (1 + kTau / 1e-2)).epsilon(1e-3).scale(0));
}

TEST_CASE("viscous bond: the breakage criterion sees the arm's stress") {
  const auto p = viscous_params();
  const beam::BeamBond model(p);
  const double E = p.youngs_modulus, sc = p.critical_stress;
  const double eps = 0.6 * sc / E;  // 40 % below the static strength
  {
    Pair slow(model);
    ramp(slow, model, 0, eps, 20000);  // over 100 tau_r
    CHECK_FALSE(slow.broken());
  }
  Pair fast(model);
  fast.set(eps);  // in one step of 1e-6 s: the arm adds ~eps
  fast.axial_force(model);
  REQUIRE(fast.broken());
  const double x = fast.scene.dt / kTau;
  const double gain = (1 - std::exp(-x)) / x;
  CHECK(fast.scene.stress[0].sigma_vm == doctest::Approx(0.6 * sc * (1 + gain)).epsilon(1e-9));
}

TEST_CASE("viscous bond: the stable step is the elastic one over sqrt(1 + beta), whatever tau_v") {
  auto p = table_one_params();
  const beam::BeamBond elastic(p);
  Pair a(elastic);
  const double t0 = elastic.time_step_limit(a.scene.batch(elastic)).critical;
  for (const double tau : {2e-6, 2e-4, 1e-1})
    for (const double beta : {1.0, 3.0}) {
      p.effects.viscosity_time = tau;
      p.effects.viscous_modulus_ratio = beta;
      const beam::BeamBond viscous(p);
      Pair b(viscous);
      const double t1 = viscous.time_step_limit(b.scene.batch(viscous)).critical;
      CHECK(t1 / t0 == doctest::Approx(1 / std::sqrt(1 + beta)).epsilon(1e-12));
    }
}

TEST_CASE("bond state: beam_bond's 9 doubles without effects, 11 with any, 23 with the Maxwell arm") {
  auto p = table_one_params();
  CHECK(beam::BeamBond(p).state_size() == beam::kStateSize);
  CHECK_FALSE(beam::BeamBond(p).with_effects());
  p.effects.viscosity_time = kTau;
  CHECK(beam::BeamBond(p).state_size() == beam::kViscousStateSize);
  p = table_one_params();
  p.effects.named = {"viscosity"};  // named at its neutral value: the effects variant without an arm
  CHECK(beam::BeamBond(p).state_size() == beam::kEffectsStateSize);
  p.effects.compression_stiffness_ratio = 2;
  CHECK(beam::BeamBond(p).state_size() == beam::kEffectsStateSize);
}

}  // namespace shard::effects_test
