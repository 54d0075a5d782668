// Cohesive softening: a pair pulled quasi-statically carries E_b A_b eps up to sigma_crit, then a
// force falling linearly to zero at eps_f = (1 + s) sigma_crit / E_b where it breaks; the work to
// break is sigma_crit A_b l0 eps_f / 2; unloading runs along the damaged secant.
#include <doctest/doctest.h>

#include <cmath>

#include "beam_effects_setup.hpp"

namespace shard::effects_test {

TEST_CASE("softening: linear to the peak, linear to zero, work to break (1 + s) times the peak energy") {
  auto p = table_one_params();
  p.effects.softening_ratio = 2;
  const beam::BeamBond model(p);
  Pair pair(model);
  const double E = p.youngs_modulus, sc = p.critical_stress, A = Pair::area, l0 = Pair::l0;
  const double eps0 = sc / E, eps_f = eps0 * (1 + p.effects.softening_ratio);
  const double peak_force = sc * A;

  // 3000 equal strain steps to 1.01 eps_f: eps0 and eps_f are grid points (1/3 and 1 of 3000 * ...).
  const int steps = 3030;
  const double h = eps_f / 3000;
  double work = 0, previous_force = 0, max_linear_error = 0;
  bool broke = false;
  double broke_at = 0;
  for (int n = 1; n <= steps && !broke; ++n) {
    const double eps = h * n;
    pair.set(eps);
    const double f = pair.axial_force(model);
    if (pair.broken()) {
      broke = true;
      broke_at = eps;
      work += 0.5 * previous_force * h * l0;  // the force falls to zero over the last step
      break;
    }
    const double expected = eps <= eps0 ? E * A * eps : peak_force * (eps_f - eps) / (eps_f - eps0);
    max_linear_error = std::max(max_linear_error, std::abs(f - expected) / peak_force);
    work += 0.5 * (f + previous_force) * h * l0;
    previous_force = f;
  }
  const double expected_work = 0.5 * sc * A * l0 * eps_f;
  MESSAGE("max deviation from the bilinear law: ", max_linear_error, " of the peak force; work ", work,
          " J vs ", expected_work, " J");
  CHECK(max_linear_error < 1e-9);
  REQUIRE(broke);
  CHECK(broke_at == doctest::Approx(eps_f).epsilon(2 * h / eps_f).scale(0));
  // Trapezoid rule is exact on a piecewise-linear curve whose kinks are grid points; the last
  // step is a triangle ending at eps_f within one step h.
  CHECK(work == doctest::Approx(expected_work).epsilon(2e-3).scale(0));
  // Against brittle (s = 0): work is (1 + s) times the elastic energy at the peak.
  CHECK(work / (0.5 * peak_force * eps0 * l0) == doctest::Approx(1 + p.effects.softening_ratio).epsilon(2e-3));
}

TEST_CASE("softening: damage is irreversible, unloading follows the secant, stored energy scales by 1 - D") {
  auto p = table_one_params();
  p.effects.softening_ratio = 1;
  const beam::BeamBond model(p);
  Pair pair(model);
  const double E = p.youngs_modulus, sc = p.critical_stress, A = Pair::area, l0 = Pair::l0;
  const double eps0 = sc / E, eps_f = 2 * eps0;
  const double eps_mid = 1.5 * eps0;  // half way down: force sc A / 2, D = 1 - (sc/2)/(E eps_mid) = 2/3
  pair.set(eps_mid);
  const double f_mid = pair.axial_force(model);
  CHECK(f_mid == doctest::Approx(0.5 * sc * A).epsilon(1e-9));
  CHECK(pair.damage() == doctest::Approx(2.0 / 3).epsilon(1e-9));

  const double eps_back = 0.5 * eps0;
  pair.set(eps_back);
  const double f_back = pair.axial_force(model);
  CHECK(f_back == doctest::Approx((1 - 2.0 / 3) * E * A * eps_back).epsilon(1e-9));
  CHECK(pair.scene.energy[0] == doctest::Approx(0.5 * (1.0 / 3) * E * A * l0 * eps_back * eps_back).epsilon(1e-9).scale(0));
  CHECK(pair.damage() == doctest::Approx(2.0 / 3).epsilon(1e-12));  // unloading does not heal

  // Reloading to eps_mid meets the softening line where it was left, then follows it down.
  pair.set(eps_mid);
  CHECK(pair.axial_force(model) == doctest::Approx(f_mid).epsilon(1e-9));
  pair.set(1.75 * eps0);
  CHECK(pair.axial_force(model) == doctest::Approx(0.25 * sc * A).epsilon(1e-9));
  pair.set(eps_f * (1 + 1e-9));
  pair.axial_force(model);
  CHECK(pair.broken());
}

TEST_CASE("softening ratio 0 is brittle: the bond breaks the step sigma_vm reaches sigma_crit") {
  const auto p = table_one_params();
  const beam::BeamBond model(p);
  Pair pair(model);
  const double eps0 = p.critical_stress / p.youngs_modulus;
  pair.set(eps0 * (1 - 1e-9));
  CHECK(pair.axial_force(model) == doctest::Approx(p.critical_stress * Pair::area).epsilon(1e-8));
  CHECK_FALSE(pair.broken());
  pair.set(eps0 * (1 + 1e-9));
  pair.axial_force(model);
  CHECK(pair.broken());
}

}  // namespace shard::effects_test
