#pragma once
// The beam bond's parameters (seed eq. 3-10, Table I defaults), shared by every plugin built on it.
#include <limits>
#include <optional>
#include <vector>

#include "shard/params.hpp"

namespace shard::beam {

ParamSpec number_param(const char* name, const char* unit, const char* doc, double value, double min,
                       bool min_exclusive, double max = std::numeric_limits<double>::infinity(),
                       std::optional<double> neutral = std::nullopt);

// youngs_modulus ... critical_stress, breakage, then `effects` and the effect policies' parameters
// (effects/bond_effects.hpp): the schema of bond/beam_bond.
std::vector<ParamSpec> beam_bond_params();

}  // namespace shard::beam
