#pragma once
// The kinetic energy that can make a loading test dynamic: the particles' kinetic energy less
// that of the rigid-body motion of them all (the centre of mass's translation and the rotation
// that carries their angular momentum about it, ω = J⁻¹ L with J the system's inertia tensor,
// particle spins included). A beam sliding along low-friction rollers, or sinking as a whole
// onto its supports, moves without straining anything: counted in the total kinetic energy it
// read as a dynamic test (a lubricated-roller run of the tiny beam at 0.02 m/s: kinetic/elastic
// 6.9 from the total, docs/explanation/diagnosis.md "Lab rates and dynamics"). The deformation's own
// motion, vibration and the quasi-static deflection velocity, stays.
#include "shard/particles.hpp"

namespace shard::analysis {

// 0.5 Σ (m v² + I ω²) minus the rigid-body part; 0 for fewer than two particles, never negative.
double deformation_kinetic_energy(const Particles& p);

}  // namespace shard::analysis
