#include "drift_lanes.hpp"

#include <cmath>

#include "shard/lane_select.hpp"
#include "shard/particles.hpp"

namespace shard {

// The clones run 2, 4 and 8 lanes of the same IEEE operations; the file is compiled with
// -ffp-contract=off (no multiply-add fused in any clone). Not under ASan: an ifunc resolver may run
// before the sanitizer runtime is initialised.
#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void kick_and_drift(const DriftLanes& p, std::size_t begin, std::size_t end, double h, double dt, double* angle,
                    double* axis) {
  double* x = p.position;
  double* v = p.velocity;
  double* w = p.omega;
  const double* f = p.force;
  const double* t = p.torque;
  const double* mass = p.mass;
  const double* inertia = p.inertia;
  const std::uint8_t* flags = p.flags;
#pragma GCC ivdep
  for (std::size_t k = begin; k < end; ++k) {
    const bool fixed = (flags[k] & kFixed) != 0;
    const bool held = (flags[k] & (kFixed | kPrescribed)) != 0;
    // v += h * F / m, omega += h * T / I (Eigen: (h * F_c) / m per component).
    const double m = mass[k], I = inertia[k];
    const double vx = lane_select(held, v[3 * k], v[3 * k] + h * f[3 * k] / m);
    const double vy = lane_select(held, v[3 * k + 1], v[3 * k + 1] + h * f[3 * k + 1] / m);
    const double vz = lane_select(held, v[3 * k + 2], v[3 * k + 2] + h * f[3 * k + 2] / m);
    const double wx = lane_select(held, w[3 * k], w[3 * k] + h * t[3 * k] / I);
    const double wy = lane_select(held, w[3 * k + 1], w[3 * k + 1] + h * t[3 * k + 1] / I);
    const double wz = lane_select(held, w[3 * k + 2], w[3 * k + 2] + h * t[3 * k + 2] / I);
    v[3 * k] = vx;
    v[3 * k + 1] = vy;
    v[3 * k + 2] = vz;
    w[3 * k] = wx;
    w[3 * k + 1] = wy;
    w[3 * k + 2] = wz;
    x[3 * k] = lane_select(fixed, x[3 * k], x[3 * k] + dt * vx);
    x[3 * k + 1] = lane_select(fixed, x[3 * k + 1], x[3 * k + 1] + dt * vy);
    x[3 * k + 2] = lane_select(fixed, x[3 * k + 2], x[3 * k + 2] + dt * vz);
    // |omega| dt and omega / |omega| (Eigen's norm: the first two squares as one packet).
    const double norm = std::sqrt((wx * wx + wy * wy) + wz * wz);
    angle[k] = lane_select(fixed, 0.0, norm * dt);
    axis[3 * k] = wx / norm;
    axis[3 * k + 1] = wy / norm;
    axis[3 * k + 2] = wz / norm;
  }
}

#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void turn(const DriftLanes& p, std::size_t begin, std::size_t end, const double* angle, const double* rotation) {
  double* q = p.orientation;
#pragma GCC ivdep
  for (std::size_t k = begin; k < end; ++k) {
    const double ax = rotation[4 * k], ay = rotation[4 * k + 1], az = rotation[4 * k + 2], aw = rotation[4 * k + 3];
    const double bx = q[4 * k], by = q[4 * k + 1], bz = q[4 * k + 2], bw = q[4 * k + 3];
    // Eigen 3.4's SSE product of double quaternions (Geometry/arch/Geometry_SIMD.h), term for term.
    const double x = (aw * bx + ay * bz) - (az * by - ax * bw);
    const double y = (aw * by + ay * bw) + (az * bx - ax * bz);
    const double z = (aw * bz - ay * bx) + (az * bw + ax * by);
    const double w = (aw * bw - ay * by) - (az * bz + ax * bx);
    // normalize(): the squared norm of the packets (x, y) and (z, w), divided only when > 0.
    const double n2 = (x * x + z * z) + (y * y + w * w);
    const double root = std::sqrt(n2);
    const bool scale = n2 > 0.0;
    const bool turns = angle[k] > 0.0;
    q[4 * k] = lane_select(turns, lane_select(scale, x / root, x), bx);
    q[4 * k + 1] = lane_select(turns, lane_select(scale, y / root, y), by);
    q[4 * k + 2] = lane_select(turns, lane_select(scale, z / root, z), bz);
    q[4 * k + 3] = lane_select(turns, lane_select(scale, w / root, w), bw);
  }
}

}  // namespace shard
