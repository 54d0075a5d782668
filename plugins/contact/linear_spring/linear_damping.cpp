#include "linear_damping.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "../common/restitution_inverse.hpp"

namespace shard::linear {

// In units with k = m* = v0 = 1 the overlap is x(t) with x'' = -x - 2 zeta x'.
double restitution_for_damping_ratio(double zeta) {
  if (!(zeta >= 0.0)) throw std::invalid_argument("damping ratio must be >= 0");
  if (zeta < 1.0) {
    // x = exp(-zeta t) sin(w t) / w; the force x + 2 zeta x' vanishes at w t = theta.
    const double w = std::sqrt(1.0 - zeta * zeta);
    const double theta = std::numbers::pi - std::atan2(2.0 * zeta * w, 1.0 - 2.0 * zeta * zeta);
    return std::exp(-zeta * theta / w) * (zeta * std::sin(theta) / w - std::cos(theta));
  }
  if (zeta == 1.0) {
    // x = t exp(-t); the force vanishes at t = 2.
    return std::exp(-2.0);
  }
  // x = exp(-zeta t) sinh(s t) / s; the force vanishes where tanh(s t) = 2 zeta s / (2 zeta^2 - 1).
  const double s = std::sqrt(zeta * zeta - 1.0);
  const double st = std::atanh(2.0 * zeta * s / (2.0 * zeta * zeta - 1.0));
  return std::exp(-zeta * st / s) * (zeta * std::sinh(st) / s - std::cosh(st));
}

double damping_ratio_for_restitution(double e) {
  return contact::damping_for_restitution(e, restitution_for_damping_ratio, 1e-14);
}

}  // namespace shard::linear
