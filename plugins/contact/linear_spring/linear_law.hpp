#pragma once
// The linear spring-dashpot law for any lane type (shard/lanes/lanes.hpp): F_n = max(0, k_n delta -
// gamma v_n), gamma = 2 zeta sqrt(k_n m*); tangential spring k_t with dashpot 2 zeta sqrt(k_t m*)
// (README.md, "Normal"). The tangential spring, friction and the effect policies are the shared
// loop's (../common/contact_lanes.hpp). Each lane performs the operations of
// linear_equations.hpp in their order, so the result does not depend on the lane width.
#include "../common/contact_lanes.hpp"

namespace shard::linear {

// One pair of materials' constants (a row of the law table, ../common/contact_lanes.hpp).
struct LinearLaw {
  enum Constant : std::size_t {
    kNormalStiffness,      // k_n, N/m
    kTangentialStiffness,  // k_t, N/m
    kTwiceZeta,            // 2 zeta, the dashpot's factor on sqrt(k m*)
    kFriction,             // mu
    kConstants
  };
  double constant[kConstants];

  template <class T>
  static contact::NormalPart<T> normal(const T* c, const T& delta, const T& /*R*/, const T& m, const T& v_n) {
    using namespace lanes;
    const T k_n = c[kNormalStiffness], k_t = c[kTangentialStiffness], two_zeta = c[kTwiceZeta];
    const T f_n = clamp_at_zero(k_n * delta - two_zeta * sqrt(k_n * m) * v_n);
    return {f_n, T(0.5) * k_n * delta * delta, k_t, two_zeta * sqrt(k_t * m)};
  }
};

}  // namespace shard::linear
