#pragma once
// The Hertz-Mindlin law for any lane type (shard/lanes/lanes.hpp): Hertz normal spring, restitution
// dashpot, Mindlin no-slip tangential stiffness (README.md; docs/explanation/physics.md, "Forces"). The tangential spring, friction
// and the effect policies are the shared loop's (../common/contact_lanes.hpp).
//
// The constant factors are formed as the equations of hertz_equations.hpp form them, left to
// right, and each lane performs those equations' IEEE operations in the same order, so the result
// does not depend on the lane width (and equals that of the per-contact Eigen code this replaced:
// the state hashes in docs/explanation/performance.md are unchanged).
#include "../common/contact_lanes.hpp"

namespace shard::hertz {

// One pair of materials' constants (a row of the law table, ../common/contact_lanes.hpp).
struct HertzLaw {
  enum Constant : std::size_t {
    kForceFactor,       // 4/3 E*
    kEnergyFactor,      // 8/15 E*
    kNormalFactor,      // 2 E*
    kTangentialFactor,  // 8 G*
    kDamping,           // dimensionless c of both dashpots c sqrt(S m*)
    kFriction,          // mu
    kConstants
  };
  double constant[kConstants];

  static HertzLaw of(double e_star, double g_star, double damping, double friction) {
    return {{4.0 / 3.0 * e_star, 8.0 / 15.0 * e_star, 2.0 * e_star, 8.0 * g_star, damping, friction}};
  }

  template <class T>
  static contact::NormalPart<T> normal(const T* c, const T& delta, const T& R, const T& m, const T& v_n) {
    using namespace lanes;
    const T root_r = sqrt(R), root_delta = sqrt(delta), root_r_delta = sqrt(R * delta);
    const T& damping = c[kDamping];
    // F_n = max(0, 4/3 E* sqrt(R*) delta^1.5 - c sqrt(S_n m*) v_n), S_n = 2 E* sqrt(R* delta): never pulling.
    const T s_n = c[kNormalFactor] * root_r_delta;
    const T elastic = c[kForceFactor] * root_r * delta * root_delta;
    const T f_n = clamp_at_zero(elastic - damping * sqrt(s_n * m) * v_n);
    // S_t = 8 G* sqrt(R* delta), c_t = c sqrt(S_t m*); U_n = 8/15 E* sqrt(R*) delta^2.5.
    const T s_t = c[kTangentialFactor] * root_r_delta;
    return {f_n, c[kEnergyFactor] * root_r * delta * delta * root_delta, s_t, damping * sqrt(s_t * m)};
  }
};

}  // namespace shard::hertz
