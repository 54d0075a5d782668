#pragma once
// The scalar rule of a touching particle pair, one slot of a tile (contact_geometry.hpp): the
// contact pass (simulation.cpp) runs it for the slots no AVX-512 lanes take, and the lanes' test
// takes it as the reference. Written out component by component in the order of the Vec3
// expressions it stands for (a - b, squaredNorm as (x x + y y) + z z, d / dist, s * n, cross
// products coefficient by coefficient), which the lanes (contact_geometry_avx512.cpp) repeat
// operation for operation: the same bits. That holds while no product is fused into a sum where
// this is compiled (the default instruction set has no FMA). Always inlined: it runs once per
// touching pair in the step loop.
#include <cmath>
#include <cstddef>

#include "contact_geometry.hpp"

namespace shard {

// Slot c's geometry; its pair (i[c], j[c]) must be two particles (j[c] >= 0).
[[gnu::always_inline]] inline void particle_pair_geometry(const PairGeometryTile& t, std::size_t c) {
  const std::size_t a = static_cast<std::size_t>(t.i[c]), b = static_cast<std::size_t>(t.j[c]);
  const double* xa = t.position + 3 * a;
  const double* xb = t.position + 3 * b;
  const double dx = xa[0] - xb[0], dy = xa[1] - xb[1], dz = xa[2] - xb[2];
  const double dist = std::sqrt((dx * dx + dy * dy) + dz * dz);
  const double ra = t.radius[a], rb = t.radius[b];
  const double reach = ra + rb;
  const double nx = dx / dist, ny = dy / dist, nz = dz / dist;
  const double overlap = reach - dist;
  const double sa = -(ra - 0.5 * overlap), sb = rb - 0.5 * overlap;
  const double ax = sa * nx, ay = sa * ny, az = sa * nz;  // arm_a
  const double bx = sb * nx, by = sb * ny, bz = sb * nz;  // arm_b
  const double* va = t.velocity + 3 * a;
  const double* vb = t.velocity + 3 * b;
  const double* wa = t.omega + 3 * a;
  const double* wb = t.omega + 3 * b;
  // vel_b = v_b + w_b x arm_b; velocity = (v_a + w_a x arm_a) - vel_b
  const double ubx = vb[0] + (wb[1] * bz - wb[2] * by);
  const double uby = vb[1] + (wb[2] * bx - wb[0] * bz);
  const double ubz = vb[2] + (wb[0] * by - wb[1] * bx);
  double* n = t.normal + 3 * c;
  n[0] = nx, n[1] = ny, n[2] = nz;
  double* v = t.velocity_rel + 3 * c;
  v[0] = (va[0] + (wa[1] * az - wa[2] * ay)) - ubx;
  v[1] = (va[1] + (wa[2] * ax - wa[0] * az)) - uby;
  v[2] = (va[2] + (wa[0] * ay - wa[1] * ax)) - ubz;
  double* w = t.omega_rel + 3 * c;
  w[0] = wa[0] - wb[0], w[1] = wa[1] - wb[1], w[2] = wa[2] - wb[2];
  t.overlap[c] = overlap;
  t.r_eff[c] = ra * rb / reach;
  const double ma = t.mass[a], mb = t.mass[b];
  t.m_eff[c] = ma * mb / (ma + mb);
}

// Slot c's torques on the ends of its particle pair (j[c] >= 0): arm_a x f + couple on end a,
// arm_b x (-f) - couple on end b, with f negated first.
[[gnu::always_inline]] inline void particle_pair_loads(const PairLoadsTile& t, std::size_t c) {
  const std::size_t a = static_cast<std::size_t>(t.i[c]), b = static_cast<std::size_t>(t.j[c]);
  const double* f = t.force + 3 * c;
  const double* n = t.normal + 3 * c;
  const double* couple = t.couple + 3 * c;
  const double overlap = t.overlap[c];
  const double fx = f[0], fy = f[1], fz = f[2];
  const double sa = -(t.radius[a] - 0.5 * overlap), sb = t.radius[b] - 0.5 * overlap;
  const double ax = sa * n[0], ay = sa * n[1], az = sa * n[2];
  const double bx = sb * n[0], by = sb * n[1], bz = sb * n[2];
  double* load_a = t.torque_a + 3 * c;
  load_a[0] = (ay * fz - az * fy) + couple[0];
  load_a[1] = (az * fx - ax * fz) + couple[1];
  load_a[2] = (ax * fy - ay * fx) + couple[2];
  const double gx = -fx, gy = -fy, gz = -fz;
  double* load_b = t.torque_b + 3 * c;
  load_b[0] = (by * gz - bz * gy) - couple[0];
  load_b[1] = (bz * gx - bx * gz) - couple[1];
  load_b[2] = (bx * gy - by * gx) - couple[2];
}

}  // namespace shard
