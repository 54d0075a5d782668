#pragma once
// The Hertz-Mindlin law for any lane type (shard/lanes/lanes.hpp): Hertz normal spring, restitution
// dashpot, Mindlin no-slip tangential stiffness (README.md; docs/physics.md, "Forces"). The tangential spring, friction
// and the effect policies are the shared loop's (../common/contact_lanes.hpp).
//
// The constant factors are formed as the equations of hertz_equations.hpp form them, left to
// right, and each lane performs those equations' IEEE operations in the same order, so the result
// does not depend on the lane width (and equals that of the per-contact Eigen code this replaced:
// the state hashes in docs/performance.md are unchanged).
#include "../common/contact_lanes.hpp"

namespace shard::hertz {

struct HertzLaw {
  double force_factor;       // 4/3 E*
  double energy_factor;      // 8/15 E*
  double normal_factor;      // 2 E*
  double tangential_factor;  // 8 G*
  double damping;            // dimensionless c of both dashpots c sqrt(S m*)
  double friction;           // mu

  static HertzLaw of(double e_star, double g_star, double damping, double friction) {
    return {4.0 / 3.0 * e_star, 8.0 / 15.0 * e_star, 2.0 * e_star, 8.0 * g_star, damping, friction};
  }

  template <class T>
  contact::NormalPart<T> normal(const T& delta, const T& R, const T& m, const T& v_n) const {
    using namespace lanes;
    const T root_r = sqrt(R), root_delta = sqrt(delta), root_r_delta = sqrt(R * delta);
    const T c(damping);
    // F_n = max(0, 4/3 E* sqrt(R*) delta^1.5 - c sqrt(S_n m*) v_n), S_n = 2 E* sqrt(R* delta): never pulling.
    const T s_n = T(normal_factor) * root_r_delta;
    const T elastic = T(force_factor) * root_r * delta * root_delta;
    const T f_n = clamp_at_zero(elastic - c * sqrt(s_n * m) * v_n);
    // S_t = 8 G* sqrt(R* delta), c_t = c sqrt(S_t m*); U_n = 8/15 E* sqrt(R*) delta^2.5.
    const T s_t = T(tangential_factor) * root_r_delta;
    return {f_n, T(energy_factor) * root_r * delta * delta * root_delta, s_t, c * sqrt(s_t * m)};
  }
};

}  // namespace shard::hertz
