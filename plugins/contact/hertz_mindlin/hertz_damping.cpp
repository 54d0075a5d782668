#include "hertz_damping.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "../common/restitution_inverse.hpp"

namespace shard::hertz {
namespace {

struct Phase {
  double y;  // dimensionless overlap
  double u;  // its rate
};

// Clamped: a contact pushes, it never pulls (the dashpot alone would pull at the end of the
// restitution phase).
double acceleration(const Phase& p, double c_scaled) {
  const double y = std::max(p.y, 0.0);
  const double root = std::sqrt(y);
  return -std::max(0.0, y * root + c_scaled * std::sqrt(root) * p.u);
}

Phase rk4_step(const Phase& p, double c_scaled, double h) {
  auto rate = [c_scaled](const Phase& q) { return Phase{q.u, acceleration(q, c_scaled)}; };
  const Phase k1 = rate(p);
  const Phase k2 = rate({p.y + 0.5 * h * k1.y, p.u + 0.5 * h * k1.u});
  const Phase k3 = rate({p.y + 0.5 * h * k2.y, p.u + 0.5 * h * k2.u});
  const Phase k4 = rate({p.y + h * k3.y, p.u + h * k3.u});
  return {p.y + h / 6.0 * (k1.y + 2.0 * k2.y + 2.0 * k3.y + k4.y),
          p.u + h / 6.0 * (k1.u + 2.0 * k2.u + 2.0 * k3.u + k4.u)};
}

}  // namespace

double restitution_for_damping(double c, double h) {
  if (!(c >= 0.0) || !(h > 0.0)) throw std::invalid_argument("restitution_for_damping: c >= 0, h > 0");
  const double c_scaled = c * std::sqrt(1.5);
  // The undamped contact lasts s = 3.22; a heavily damped one creeps out over a longer time.
  // A particle still in touch after this long has, for any purpose, stopped.
  const double s_max = 1e3;
  Phase p{0.0, 1.0};
  for (double s = 0.0; s < s_max; s += h) {
    p = rk4_step(p, c_scaled, h);
    // Near y = 0 the clamp holds the force at zero, so u is the constant exit speed.
    if (p.y < 0.0) return -p.u;
  }
  return 0.0;
}

double damping_for_restitution(double e) {
  return contact::damping_for_restitution(e, [](double c) { return restitution_for_damping(c); }, 1e-12);
}

}  // namespace shard::hertz
