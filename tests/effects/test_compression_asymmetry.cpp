// Tension/compression asymmetry: the axial stiffness of a shortened bond is ratio E_b A_b / l0,
// of a stretched one E_b A_b / l0; the stored energy follows each branch.
#include <doctest/doctest.h>

#include <cmath>

#include "beam_effects_setup.hpp"

namespace shard::effects_test {

TEST_CASE("compression stiffness ratio scales the axial stiffness in compression only") {
  auto p = table_one_params();
  p.effects.compression_stiffness_ratio = 3;
  const beam::BeamBond model(p);
  Pair pair(model);
  const double E = p.youngs_modulus, A = Pair::area, l0 = Pair::l0;
  const double eps = 2e-3;
  pair.set(-eps);
  const double f_compression = pair.axial_force(model);
  CHECK(pair.scene.energy[0] == doctest::Approx(0.5 * 3 * E * A * l0 * eps * eps).epsilon(1e-10).scale(0));
  pair.set(eps);
  const double f_tension = pair.axial_force(model);
  CHECK(f_tension == doctest::Approx(E * A * eps).epsilon(1e-10));
  CHECK(f_compression == doctest::Approx(-3 * E * A * eps).epsilon(1e-10));
  // Measured as stiffness (secant through the unstrained state): the ratio of the two branches.
  CHECK(-f_compression / f_tension == doctest::Approx(3).epsilon(1e-9));

  // Compression does not count towards the von Mises criterion: 3x the tensile strain at break
  // in compression leaves the bond intact.
  pair.set(-3 * p.critical_stress / E);
  pair.axial_force(model);
  CHECK_FALSE(pair.broken());
}

TEST_CASE("a stiffer compressive branch shortens the bond time step by 1/sqrt(ratio)") {
  auto p = table_one_params();
  const beam::BeamBond symmetric(p);
  p.effects.compression_stiffness_ratio = 4;
  const beam::BeamBond stiff(p);
  p.effects.compression_stiffness_ratio = 0.25;
  const beam::BeamBond soft(p);
  Pair a(symmetric), b(stiff), c(soft);
  const double t0 = symmetric.time_step_limit(a.scene.batch(symmetric)).critical;
  CHECK(stiff.time_step_limit(b.scene.batch(stiff)).critical == doctest::Approx(t0 / 2).epsilon(1e-12).scale(0));
  CHECK(soft.time_step_limit(c.scene.batch(soft)).critical == doctest::Approx(t0).epsilon(1e-12).scale(0));
}

}  // namespace shard::effects_test
