#pragma once
// Parameter schemas shared by the contact plugins: one definition of each physical parameter.
#include <optional>

#include "shard/params.hpp"

namespace shard::contact_params {

inline ParamSpec shear_modulus(double default_value) {
  return {.name = "shear_modulus", .unit = "Pa",
          .doc = "shear modulus G of the particles (walls are taken of the same material unless they name their own)",
          .default_value = default_value, .min = 0.0, .min_exclusive = true, .neutral = std::nullopt,
          .scope = ParamScope::Material};
}

inline ParamSpec poisson_ratio(double default_value) {
  return {.name = "poisson_ratio", .unit = "1", .doc = "Poisson's ratio nu (not given in the seed; 0.25 is common)",
          .default_value = default_value, .min = -1.0, .max = 0.5, .min_exclusive = true, .neutral = std::nullopt,
          .scope = ParamScope::Material};
}

inline ParamSpec friction(double default_value) {
  return {.name = "friction", .unit = "1", .doc = "Coulomb sliding friction coefficient mu, |F_t| <= mu F_n",
          .default_value = default_value, .min = 0.0, .max = 10.0, .neutral = 0.0, .scope = ParamScope::Pair};
}

inline ParamSpec restitution(double default_value) {
  return {.name = "restitution", .unit = "1",
          .doc = "normal coefficient of restitution e, realised exactly for any impact speed",
          .default_value = default_value, .min = 0.0, .max = 1.0, .min_exclusive = true, .neutral = 1.0,
          .scope = ParamScope::Pair};
}

}  // namespace shard::contact_params
