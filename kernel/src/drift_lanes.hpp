#pragma once
// The first half of the velocity-Verlet step (Simulation::integrate_first_half) as two loops
// without branches, which GCC runs in SIMD lanes, around the scalar sin/cos of the rotation
// (libm's, which no SIMD version reproduces bit for bit). Each lane performs the IEEE operations
// of the Eigen expressions it replaces, in Eigen's order, so the state is the same to the bit.
#include <cstddef>
#include <cstdint>

namespace shard {

struct DriftLanes {
  double* position;      // 3 per particle
  double* velocity;      // 3 per particle
  double* omega;         // 3 per particle
  double* orientation;   // 4 per particle, Eigen's order x, y, z, w
  const double* force;   // 3 per particle
  const double* torque;  // 3 per particle
  const double* mass;
  const double* inertia;
  const std::uint8_t* flags;
};

// Half kick (not for fixed or prescribed particles) and drift (not for fixed ones) of particles
// [begin, end); angle[k] = |omega| dt of the turn to make (0 for a fixed particle), axis[3k..]
// omega / |omega|.
void kick_and_drift(const DriftLanes& p, std::size_t begin, std::size_t end, double h, double dt, double* angle,
                    double* axis);

// orientation = normalise(rotation * orientation) where angle[k] > 0; rotation holds 4 doubles per
// particle in Eigen's order (x, y, z, w).
void turn(const DriftLanes& p, std::size_t begin, std::size_t end, const double* angle, const double* rotation);

}  // namespace shard
