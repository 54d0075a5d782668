#pragma once
// Pair contact models (plugins/contact/*/README.md). The kernel finds the touching pairs and their geometry;
// the model turns geometry into force in batch calls (blocks of touching pairs, each thread its
// own; a contact's result must not depend on the others in its batch). A model never sees the
// neighbour list, so the same model serves particle-particle and particle-wall contacts.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

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
  // Per contact, the pair of materials a * count + b (ContactMaterials) of particle i and of
  // particle j or the wall; null when the scene has one material (every contact uses its law).
  const std::int32_t* material_pair = nullptr;
};

// The scene's materials as a contact law sees them (docs/reference/materials.md): per material the law's
// ParamScope::Material parameters, per pair of materials its ParamScope::Pair parameters, with
// pair[a * count + b] == pair[b * count + a]. A pair no contact can have (two materials only
// walls are made of) holds a copy of another pair's values.
struct ContactMaterials {
  std::size_t count = 0;
  std::vector<std::string> names;
  std::vector<ParamSet> material;
  std::vector<ParamSet> pair;
};

// The particles of one material: the smallest radius and its density; min_radius 0 when no
// particle is of that material (a wall's).
struct MaterialExtent {
  double min_radius = 0;  // m
  double density = 0;     // kg/m^3
};

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  virtual std::size_t history_size() const { return 0; }
  // Stability limit for the lightest particle of this scene.
  virtual TimeStepLimit time_step_limit(double min_radius, double density) const = 0;
  virtual void compute(ContactBatch& batch) const = 0;

  // A scene with several materials: called once before the run, after which the batches carry
  // material_pair. A law without per-material or per-pair parameters keeps this default, which
  // refuses (the scene loader reports it with the [contact] section).
  virtual void set_materials(const ContactMaterials& materials) {
    (void)materials;
    throw std::invalid_argument("this contact law has no per-material or per-pair parameters, so it cannot tell "
                                "materials apart; use one material or a law that declares them (hertz_mindlin, "
                                "linear_spring)");
  }
  // The limit over the particles of several materials (after set_materials). The default takes
  // the smallest one-material limit, right for a law whose parameters are the same for all pairs.
  virtual TimeStepLimit time_step_limit(const std::vector<MaterialExtent>& per_material) const {
    TimeStepLimit out{"", std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    for (const auto& m : per_material)
      if (m.min_radius > 0) {
        const TimeStepLimit l = time_step_limit(m.min_radius, m.density);
        if (l.recommended < out.recommended) out = l;
      }
    return out;
  }
};

}  // namespace shard
