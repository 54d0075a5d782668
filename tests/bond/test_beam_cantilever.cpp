// A chain of 21 bonded spheres clamped at one end: tip deflection and rotation under an end load
// and an end moment against Timoshenko beam theory. The kernel has no per-particle external load
// yet, so the chain is relaxed here with mass-proportional damping; the bond model is the
// plugin loaded from its .so.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "beam_plugin.hpp"
#include "beam_setup.hpp"
#include "shard/simulation.hpp"

using namespace shard;
using namespace shard::test;

namespace {

constexpr int kElements = 20;
const Vec3 kBeamAxis = Vec3(1, -0.4, 0.3).normalized();
const Vec3 kLoadDir = kBeamAxis.cross(Vec3(0.3, 1, -0.2)).normalized();
const Vec3 kBendAxis = kBeamAxis.cross(kLoadDir);  // a tip load along kLoadDir turns the tip about it

struct Tip {
  double deflection;  // along kLoadDir, m
  double rotation;    // about kBendAxis, rad
};

// Relaxes the clamped chain (particle 0 held) under a tip force and moment to static equilibrium.
// Damping a v with a = 2 omega_1 makes every mode decay like exp(-omega_1 t).
Tip relax(const BondModel& model, const Vec3& tip_force, const Vec3& tip_moment, double omega_1) {
  HandBonds w;
  for (int k = 0; k <= kElements; ++k) {
    w.add_sphere(Vec3(0.001, 0.002, -0.001) + 2 * kRadius * k * kBeamAxis, kRadius, kDensity);
    w.orientation[k] = rotation(Vec3(0.1 * k, -0.2, 0.05 * k * k));
    if (k > 0) w.add_bond(k - 1, k);
  }
  const Quat tip_start = w.orientation[kElements];
  const Vec3 tip_position = w.position[kElements];
  w.initialize(model);
  BondBatch probe = w.batch(model);
  const double dt = model.time_step_limit(probe).recommended;
  const double a = 2 * omega_1;
  const int steps = static_cast<int>(30 / omega_1 / dt);  // e^-30: converged to rounding

  std::vector<Vec3> force(w.position.size()), torque(w.position.size());
  for (int s = 0; s < steps; ++s) {
    w.compute(model);
    std::fill(force.begin(), force.end(), Vec3::Zero());
    std::fill(torque.begin(), torque.end(), Vec3::Zero());
    force[kElements] += tip_force;
    torque[kElements] += tip_moment;
    for (std::size_t b = 0; b < w.i.size(); ++b) {
      force[w.i[b]] += w.force[b];
      force[w.j[b]] -= w.force[b];
      torque[w.i[b]] += w.torque_i[b];
      torque[w.j[b]] += w.torque_j[b];
    }
    for (std::size_t k = 1; k < w.position.size(); ++k) {  // symplectic Euler, particle 0 clamped
      w.velocity[k] += dt * (force[k] / w.mass[k] - a * w.velocity[k]);
      w.omega[k] += dt * (torque[k] / w.inertia[k] - a * w.omega[k]);
      w.position[k] += dt * w.velocity[k];
      turn(w, static_cast<Index>(k), dt * w.omega[k]);
    }
  }
  const Eigen::AngleAxisd turned(w.orientation[kElements] * tip_start.conjugate());
  return {(w.position[kElements] - tip_position).dot(kLoadDir), turned.angle() * turned.axis().dot(kBendAxis)};
}

}  // namespace

TEST_CASE("clamped chain of 21 spheres: end load and end moment against Timoshenko theory") {
  const BeamPlugin beam({{"rotational_damping", 0.0}, {"breakage", false}});
  const beam::BeamBondParams p;
  const BeamNumbers b = numbers_of(p);
  const double L = kElements * b.l0;
  const double EI = b.E * b.J, kGA = b.a_s * b.G * b.A;
  const double m = kDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3);
  const double omega_1 = 1.875 * 1.875 * std::sqrt(EI / (m / b.l0) / std::pow(L, 4));  // first bending mode

  SUBCASE("end load P") {
    const double P = 1e-3 * 3 * EI / (L * L);  // tip deflection ~ 1e-3 L: linear range
    const Tip tip = relax(beam.model(), P * kLoadDir, Vec3::Zero(), omega_1);
    const double timoshenko = P * L * L * L / (3 * EI) + P * L / kGA;
    // The two-node element with one-point shear integration has exact nodal rotations; its
    // deflection is the trapezoidal integral of them: the bending part times (1 - 1 / (4 n^2)).
    const double discrete = P * L * L * L / (3 * EI) * (1 - 1.0 / (4 * kElements * kElements)) + P * L / kGA;
    const double rotation = P * L * L / (2 * EI);
    std::printf("cantilever end load: tip deflection %.6g m, Timoshenko %.6g (%+.3f %%), discrete %+.4f %%; "
                "tip rotation %.6g rad, theory %.6g (%+.3f %%)\n",
                tip.deflection, timoshenko, 100 * (tip.deflection / timoshenko - 1), 100 * (tip.deflection / discrete - 1),
                tip.rotation, rotation, 100 * (tip.rotation / rotation - 1));
    CHECK(tip.deflection == doctest::Approx(timoshenko).epsilon(0.05).scale(0));
    // Geometric nonlinearity at 1e-3 rad is ~1e-6 relative; 1e-4 leaves room for relaxation.
    CHECK(tip.deflection == doctest::Approx(discrete).epsilon(1e-4).scale(0));
    CHECK(tip.rotation == doctest::Approx(rotation).epsilon(1e-4).scale(0));
  }
  SUBCASE("end moment M") {
    const double M = 1e-3 * EI / L;  // tip rotation 1e-3 rad
    const Tip tip = relax(beam.model(), Vec3::Zero(), M * kBendAxis, omega_1);
    const double rotation = M * L / EI, deflection = M * L * L / (2 * EI);
    std::printf("cantilever end moment: tip rotation %.6g rad, theory %.6g (%+.3f %%); deflection %.6g m, theory %.6g (%+.3f %%)\n",
                tip.rotation, rotation, 100 * (tip.rotation / rotation - 1), tip.deflection, deflection,
                100 * (tip.deflection / deflection - 1));
    CHECK(tip.rotation == doctest::Approx(rotation).epsilon(1e-4).scale(0));
    CHECK(tip.deflection == doctest::Approx(deflection).epsilon(1e-4).scale(0));
  }
}

// Through the kernel: particle 0 held by kFixed, gravity loads every free sphere with W = m g
// (nodal loads), Cundall damping brings the chain to rest. Discrete theory by superposition of
// the single-node solutions: a load W at a = k h gives w(a) = W a^3/(3EI) - W h^2 a/(12EI)
// + W a/(a_s G A), and the tip beyond it follows the constant rotation W a^2/(2EI).
TEST_CASE("clamped chain under its own weight in the kernel: tip deflection against beam theory") {
  const BeamPlugin beam({{"breakage", false}, {"damping", 1e-3}});
  const beam::BeamBondParams p;
  const BeamNumbers b = numbers_of(p);
  const double L = kElements * b.l0, h = b.l0;
  const double EI = b.E * b.J, kGA = b.a_s * b.G * b.A;

  SimulationSetup setup;
  for (int k = 0; k <= kElements; ++k) {
    setup.particles.add(Vec3(0.001, 0.002, -0.001) + h * k * kBeamAxis, kRadius, kDensity);
    setup.particles.orientation[k] = rotation(Vec3(0.1 * k, -0.2, 0.05 * k * k));
    if (k > 0) setup.bonds.emplace_back(k - 1, k);
  }
  setup.particles.flags[0] = kFixed;
  const double m = setup.particles.mass[0];
  const double W = 1e-3 * 8 * EI / (L * L) / kElements;  // total load n W gives ~1e-3 L deflection
  setup.gravity = W / m * kLoadDir;
  setup.global_damping = 0.7;
  setup.bond = &beam.model();
  const Vec3 tip_start = setup.particles.position[kElements];
  Simulation sim(std::move(setup));

  double discrete = 0;
  for (int k = 1; k <= kElements; ++k) {
    const double a = k * h;
    discrete += W * a * a * a / (3 * EI) - W * h * h * a / (12 * EI) + W * a / kGA + W * a * a / (2 * EI) * (L - a);
  }
  // Continuum: q = W / h over the span plus the half load W / 2 the lumping puts at the tip.
  const double q = W / h;
  const double continuum = q * std::pow(L, 4) / (8 * EI) + q * L * L / (2 * kGA) +
                           0.5 * W * L * L * L / (3 * EI) + 0.5 * W * L / kGA;

  double previous = 0, deflection = 0;
  for (int round = 0; round < 100; ++round) {
    sim.run(20000);
    deflection = (sim.particles().position[kElements] - tip_start).dot(kLoadDir);
    if (round > 0 && std::abs(deflection - previous) < 1e-7 * std::abs(deflection)) break;
    previous = deflection;
  }
  std::printf("cantilever under own weight (kernel, %lld steps): tip %.6g m, discrete %.6g (%+.4f %%), continuum %.6g (%+.3f %%)\n",
              static_cast<long long>(sim.step_count()), deflection, discrete, 100 * (deflection / discrete - 1), continuum,
              100 * (deflection / continuum - 1));
  CHECK(deflection == doctest::Approx(discrete).epsilon(1e-3).scale(0));
  CHECK(deflection == doctest::Approx(continuum).epsilon(0.05).scale(0));
  CHECK(sim.particles().position[0] == Vec3(0.001, 0.002, -0.001));  // the clamp held
}
