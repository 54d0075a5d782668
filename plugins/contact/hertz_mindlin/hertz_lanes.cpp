#include "hertz_lanes.hpp"

#include <cmath>

#include "shard/lane_select.hpp"

namespace shard::hertz {
namespace {

// Eigen's order for a 3-vector dot product and squared norm: the first two terms as one packet.
inline double dot3(double ax, double ay, double az, double bx, double by, double bz) {
  return (ax * bx + ay * by) + az * bz;
}

// std::max(0.0, x), NaN and -0 included.
inline double clamp_at_zero(double x) { return 0.0 < x ? x : 0.0; }

}  // namespace

// AVX2 and AVX-512 clones run 4 and 8 lanes of the same IEEE operations; hertz_lanes.cpp is
// compiled with -ffp-contract=off, so no clone fuses a multiply-add (the AVX-512 target enables
// FMA) and each rounds exactly as the x86-64-v2 per-contact code. Square roots and divisions are
// correctly rounded in SIMD too. Not under ASan: an ifunc resolver may run before the sanitizer
// runtime is initialised.
#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void compute_lanes(ContactBatch& batch, const LaneConstants& c) {
  const std::size_t count = batch.count;
  if (count == 0) return;
  const double* __restrict normal = batch.normal->data();
  const double* __restrict velocity = batch.velocity->data();
  const double* __restrict overlap = batch.overlap;
  const double* __restrict r_eff = batch.r_eff;
  const double* __restrict m_eff = batch.m_eff;
  double* __restrict history = batch.history;
  double* __restrict force = batch.force->data();
  double* __restrict energy = batch.energy;
  const double dt = batch.dt;
  // The constant factors as the equations' left-to-right products form them.
  const double force_factor = 4.0 / 3.0 * c.e_star;
  const double energy_factor = 8.0 / 15.0 * c.e_star;
  const double normal_factor = 2.0 * c.e_star;
  const double tangential_factor = 8.0 * c.g_star;
  const double damping = c.damping, friction = c.friction;
  // The kernel's arrays do not overlap (GCC does not take __restrict on these locals as proof).
#pragma GCC ivdep
  for (std::size_t k = 0; k < count; ++k) {
    const double nx = normal[3 * k], ny = normal[3 * k + 1], nz = normal[3 * k + 2];
    const double vx = velocity[3 * k], vy = velocity[3 * k + 1], vz = velocity[3 * k + 2];
    const double delta = overlap[k], R = r_eff[k], m = m_eff[k];
    const double root_r = std::sqrt(R), root_delta = std::sqrt(delta), root_r_delta = std::sqrt(R * delta);

    // Normal: Hertz spring and dashpot, never pulling.
    const double v_n = dot3(vx, vy, vz, nx, ny, nz);
    const double s_n = normal_factor * root_r_delta;
    const double elastic = force_factor * root_r * delta * root_delta;
    const double f_n = clamp_at_zero(elastic - damping * std::sqrt(s_n * m) * v_n);

    // Tangential spring turned onto the contact plane, keeping its length, then stretched.
    const double tx = vx - v_n * nx, ty = vy - v_n * ny, tz = vz - v_n * nz;
    const double hx = history[3 * k], hy = history[3 * k + 1], hz = history[3 * k + 2];
    const double h_n = dot3(hx, hy, hz, nx, ny, nz);
    const double px = hx - h_n * nx, py = hy - h_n * ny, pz = hz - h_n * nz;
    const double old_length = std::sqrt(dot3(hx, hy, hz, hx, hy, hz));
    const double new_length = std::sqrt(dot3(px, py, pz, px, py, pz));
    const bool flat = new_length == 0.0;
    const double scale = old_length / new_length;
    const double qx = px * scale, qy = py * scale, qz = pz * scale;
    const double xi_x = lane_select(flat, 0.0, qx) + tx * dt;
    const double xi_y = lane_select(flat, 0.0, qy) + ty * dt;
    const double xi_z = lane_select(flat, 0.0, qz) + tz * dt;

    // Spring and dashpot, capped by Coulomb; a sliding contact's spring holds the capped force.
    const double s_t = tangential_factor * root_r_delta;
    const double c_t = damping * std::sqrt(s_t * m);
    const double limit = friction * f_n;
    const double fx = -s_t * xi_x - c_t * tx, fy = -s_t * xi_y - c_t * ty, fz = -s_t * xi_z - c_t * tz;
    const double magnitude = std::sqrt(dot3(fx, fy, fz, fx, fy, fz));
    const bool sticks = magnitude <= limit;
    const double cap = limit / magnitude;
    const double cx = fx * cap, cy = fy * cap, cz = fz * cap;
    const double rx = -cx / s_t, ry = -cy / s_t, rz = -cz / s_t;
    const double ft_x = lane_select(sticks, fx, cx), ft_y = lane_select(sticks, fy, cy), ft_z = lane_select(sticks, fz, cz);
    const double sx = lane_select(sticks, xi_x, rx), sy = lane_select(sticks, xi_y, ry), sz = lane_select(sticks, xi_z, rz);
    history[3 * k] = sx;
    history[3 * k + 1] = sy;
    history[3 * k + 2] = sz;

    force[3 * k] = f_n * nx + ft_x;
    force[3 * k + 1] = f_n * ny + ft_y;
    force[3 * k + 2] = f_n * nz + ft_z;
    energy[k] = energy_factor * root_r * delta * delta * root_delta + 0.5 * s_t * dot3(sx, sy, sz, sx, sy, sz);
  }
}

}  // namespace shard::hertz
