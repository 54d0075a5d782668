#include "shard/bending/beam_theory.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace shard::bending {

void BendingGeometry::check() const {
  if (!(width > 0 && height > 0 && pin_distance > 0 && span > pin_distance))
    throw std::invalid_argument(fmt::format(
        "four-point bending geometry: need 0 < pin distance < span and positive width and height; got span {:.4g} m, "
        "pin distance {:.4g} m, width {:.4g} m, height {:.4g} m",
        span, pin_distance, width, height));
}

double compliance_factor(const BendingGeometry& g) {
  g.check();
  const double l_minus_d = g.span - g.pin_distance;
  return l_minus_d * l_minus_d * (g.span + 2.0 * g.pin_distance) / (48.0 * g.second_moment());
}

double youngs_modulus_from_stiffness(const BendingGeometry& g, double stiffness) {
  return stiffness * compliance_factor(g);
}

double stiffness_from_youngs_modulus(const BendingGeometry& g, double youngs_modulus) {
  return youngs_modulus / compliance_factor(g);
}

double flexural_stress(const BendingGeometry& g, double force) {
  g.check();
  return 3.0 * force * (g.span - g.pin_distance) / (2.0 * g.width * g.height * g.height);
}

double force_from_flexural_stress(const BendingGeometry& g, double stress) {
  return stress / flexural_stress(g, 1.0);
}

double shear_to_bending_deflection(const BendingGeometry& g, double youngs_over_shear_modulus) {
  g.check();
  constexpr double rectangular_shear_coefficient = 5.0 / 6.0;
  return youngs_over_shear_modulus * g.height * g.height /
         (rectangular_shear_coefficient * (g.span - g.pin_distance) * (g.span + 2.0 * g.pin_distance));
}

}  // namespace shard::bending
