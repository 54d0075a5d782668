#pragma once
// The effect tests drive bond models by hand exactly as the beam_bond tests do.
#include "../bond/bond_pair.hpp"

namespace shard::effects_test {

// A step of 1e-6 s: the viscous effect reads the step of the batch.
struct BondScene : test::HandBonds {
  BondScene() { dt = 1e-6; }
};

}  // namespace shard::effects_test
