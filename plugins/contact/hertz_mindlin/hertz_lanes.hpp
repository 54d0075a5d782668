#pragma once
// hertz_mindlin's batch loop written across contacts without branches, so that GCC runs it in
// SIMD lanes. Every lane performs the IEEE operations of the per-contact code
// (HertzMindlin::compute_reference: hertz_equations.hpp, ../common/tangential_spring.hpp) in the
// order Eigen evaluates them, so the two agree bit for bit (tests/contact/test_hertz_lanes.cpp).
#include "shard/contact_model.hpp"

namespace shard::hertz {

struct LaneConstants {
  double e_star;    // E*, Pa
  double g_star;    // G*, Pa
  double damping;   // dimensionless c of both dashpots
  double friction;  // mu
};

void compute_lanes(ContactBatch& batch, const LaneConstants& c);

}  // namespace shard::hertz
