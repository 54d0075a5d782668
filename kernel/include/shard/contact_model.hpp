#pragma once
// Pair contact models (plugins/contact/*/README.md). The kernel finds the touching pairs and their geometry;
// the model turns geometry into force in batch calls (blocks of touching pairs, each thread its
// own; a contact's result must not depend on the others in its batch). A model never sees the
// neighbour list, so the same model serves particle-particle and particle-wall contacts.
#include <cstddef>
#include <string>

#include "shard/params.hpp"
#include "shard/time_step.hpp"
#include "shard/types.hpp"

namespace shard {

// One step's touching pairs, structure of arrays. Index k runs over contacts.
// For a particle-wall contact j is -1 - wall_index and r_eff is the particle radius.
struct ContactBatch {
  std::size_t count = 0;
  double dt = 0;
  const Index* i = nullptr;
  const Index* j = nullptr;
  const Vec3* normal = nullptr;     // unit, from j towards i
  const double* overlap = nullptr;  // delta > 0, m
  const Vec3* velocity = nullptr;   // velocity of i relative to j at the contact point, m/s
  const Vec3* omega_rel = nullptr;  // omega_i - omega_j, rad/s
  const double* r_eff = nullptr;    // R* = r_i r_j / (r_i + r_j), m
  const double* m_eff = nullptr;    // m* = m_i m_j / (m_i + m_j), kg
  // Per-contact history owned by the kernel, `history_size()` doubles per contact, zero for a
  // new contact, kept while the pair stays in touch (also across neighbour-list rebuilds).
  double* history = nullptr;
  // Outputs, zeroed by the kernel: force on i at the contact point (j gets the opposite),
  // an extra pure couple on i (j gets the opposite), stored elastic energy.
  Vec3* force = nullptr;
  Vec3* couple = nullptr;
  double* energy = nullptr;
};

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  virtual std::size_t history_size() const { return 0; }
  // Stability limit for the lightest particle of this scene.
  virtual TimeStepLimit time_step_limit(double min_radius, double density) const = 0;
  virtual void compute(ContactBatch& batch) const = 0;
};

}  // namespace shard
