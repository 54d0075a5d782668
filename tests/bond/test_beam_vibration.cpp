// A free bonded pair vibrating in each beam mode, run by the kernel with the plugin loaded from
// its .so: energy conservation at the automatic time step, the period of each mode, and the
// logarithmic decrement of the eq. 4 and eq. 6 damping.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "beam_pair_sim.hpp"
#include "beam_plugin.hpp"

using namespace shard;
using namespace shard::test;

namespace {

double mean(const std::vector<double>& v, std::size_t begin, std::size_t end) {
  return std::accumulate(v.begin() + static_cast<std::ptrdiff_t>(begin), v.begin() + static_cast<std::ptrdiff_t>(end), 0.0) /
         static_cast<double>(end - begin);
}

}  // namespace

TEST_CASE("undamped pair: energy conserved over 1e5 auto steps, period of each mode within 1 %") {
  const BeamPlugin beam({{"rotational_damping", 0.0}, {"damping", 0.0}, {"breakage", false}});
  beam::BeamBondParams p;  // defaults of the schema, for the theory
  const BeamNumbers b = numbers_of(p);

  for (const Mode mode : {Mode::Axial, Mode::Shear, Mode::Twist, Mode::Bending}) {
    SimulationSetup setup = pair_setup(beam.model());
    const double m = setup.particles.mass[0], I = setup.particles.inertia[0];
    const ModeTheory theory = theory_of(mode, b, m, I);
    excite(setup.particles, mode, b.l0, theory.omega(), m, I);
    Simulation sim(std::move(setup));

    const std::size_t steps = 100000;
    std::vector<double> energy(steps), signal(steps);
    for (std::size_t k = 0; k < steps; ++k) {
      sim.step();
      const Energies e = sim.energies();
      energy[k] = e.kinetic + e.bond;
      signal[k] = modal_signal(sim, mode);
    }
    // Velocity Verlet keeps a bounded O((omega dt)^2) ripple; a drift is a change of its mean.
    const double start = mean(energy, 0, steps / 4), end = mean(energy, steps - steps / 4, steps);
    const double drift = std::abs(end - start) / start;
    const auto crossings = upward_crossings(signal);
    REQUIRE(crossings.size() > 10);
    const double period =
        (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1) * sim.dt();
    std::printf("beam pair %-8s dt %.4g s  omega dt %.3f  energy drift %.2e  period %.6g s (theory %.6g, %+.3f %%)\n",
                name_of(mode), sim.dt(), theory.omega() * sim.dt(), drift, period, theory.period(),
                100 * (period / theory.period() - 1));
    CAPTURE(name_of(mode));
    CHECK(sim.dt() == doctest::Approx(0.17 * std::sqrt(m / b.axial())).epsilon(1e-12));
    CHECK(drift < 1e-4);
    CHECK(period == doctest::Approx(theory.period()).epsilon(0.01).scale(0));
  }
}

TEST_CASE("damped pair: logarithmic decrement of eq. 4 and eq. 6 within 2 %") {
  const double zeta = 0.02;  // damping ratio aimed at
  beam::BeamBondParams p;
  const BeamNumbers b = numbers_of(p);
  SimulationSetup probe = pair_setup(beam::BeamBond(p));
  const double m = probe.particles.mass[0], I = probe.particles.inertia[0];

  for (const Mode mode : {Mode::Axial, Mode::Shear, Mode::Twist, Mode::Bending}) {
    const ModeTheory theory = theory_of(mode, b, m, I);
    const bool rotational = mode == Mode::Twist || mode == Mode::Bending;
    // Eq. 4: zeta = d / (2 sqrt(K m_eff)). Eq. 6: c = f sqrt(K I_r), so zeta = f / 2.
    const double d = rotational ? 0.0 : 2 * zeta * std::sqrt(theory.stiffness * theory.inertia);
    const double factor = rotational ? 2 * zeta : 0.0;
    const BeamPlugin beam({{"rotational_damping", factor}, {"damping", d}, {"breakage", false}});

    SimulationSetup setup = pair_setup(beam.model());
    excite(setup.particles, mode, b.l0, theory.omega(), m, I);
    Simulation sim(std::move(setup));
    const auto steps_per_period = static_cast<std::size_t>(theory.period() / sim.dt());
    const std::size_t cycles = 10;
    std::vector<double> signal;
    for (std::size_t k = 0; k < (cycles + 2) * steps_per_period; ++k) {
      sim.step();
      signal.push_back(modal_signal(sim, mode));
    }
    const auto peaks = peak_heights(signal);
    REQUIRE(peaks.size() > cycles);
    const double decrement = std::log(peaks[0] / peaks[cycles]) / static_cast<double>(cycles);
    const double expected = 2 * std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta);
    std::printf("beam pair %-8s log decrement %.5f (theory %.5f, %+.2f %%)\n", name_of(mode), decrement, expected,
                100 * (decrement / expected - 1));
    CAPTURE(name_of(mode));
    CHECK(decrement == doctest::Approx(expected).epsilon(0.02).scale(0));
  }
}
