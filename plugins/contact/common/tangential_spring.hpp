#pragma once
// The incremental tangential spring with Coulomb friction shared by the contact models
// (hertz_mindlin/README.md). The spring's extension xi lives in the kernel's per-contact history
// (3 doubles); these functions are the three equations applied to it each step.
#include <cstddef>

#include "shard/types.hpp"

namespace shard::contact {

inline constexpr std::size_t kTangentialHistorySize = 3;

inline Vec3 load_spring(const double* history) { return {history[0], history[1], history[2]}; }

inline void store_spring(double* history, const Vec3& xi) {
  history[0] = xi.x();
  history[1] = xi.y();
  history[2] = xi.z();
}

inline Vec3 tangential_part(const Vec3& v, const Vec3& n) { return v - v.dot(n) * n; }

// The contact plane turns with the pair; the stored extension is turned with it. Removing the
// normal component alone would shrink the spring and leak elastic energy on every rotation, so
// the projected spring is rescaled to its old length.
inline Vec3 rotate_onto_tangent_plane(const Vec3& xi, const Vec3& n) {
  const Vec3 projected = tangential_part(xi, n);
  const double old_length = xi.norm();
  const double new_length = projected.norm();
  if (new_length == 0.0) return Vec3::Zero();
  return projected * (old_length / new_length);
}

struct TangentialState {
  Vec3 force;   // on i, N
  Vec3 spring;  // extension to store, m
};

// Elastic spring plus dashpot, capped by Coulomb: |F_t| <= mu F_n. While sliding, the spring is
// reset so that its elastic force alone equals the capped force: the contact resumes sticking
// from the cap without a jump, and the stored energy matches the force it transmits.
inline TangentialState coulomb_capped_force(const Vec3& spring, const Vec3& v_t, double stiffness,
                                            double damping, double coulomb_limit) {
  Vec3 force = -stiffness * spring - damping * v_t;
  const double magnitude = force.norm();
  if (magnitude <= coulomb_limit) return {force, spring};
  force *= coulomb_limit / magnitude;
  return {force, -force / stiffness};
}

inline double spring_energy(double stiffness, const Vec3& spring) {
  return 0.5 * stiffness * spring.squaredNorm();
}

}  // namespace shard::contact
