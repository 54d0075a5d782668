#pragma once
// Particle state as a structure of arrays: one contiguous array per field, so a batch loop
// streams only the fields it reads.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shard/types.hpp"

namespace shard {

enum ParticleFlag : std::uint8_t {
  kFixed = 1u << 0,  // position and orientation held; forces still recorded
  // Velocity and angular velocity held at their set values, position and orientation integrated:
  // a loading platen made of particles. Forces still recorded.
  kPrescribed = 1u << 1,
  // In an unbreakable zone ([[wall]] unbreakable_zone): a bond model never fails a bond whose two
  // particles carry it (bond_unbreakable) and computes it on as an intact bond.
  kUnbreakable = 1u << 2,
};

struct Particles {
  std::vector<Vec3> position;     // m
  std::vector<Vec3> velocity;     // m/s
  std::vector<Quat> orientation;  // body -> lab rotation, kept normalised
  std::vector<Vec3> omega;        // rad/s, lab frame
  std::vector<Vec3> force;        // N, accumulated each step
  std::vector<Vec3> torque;       // N m, accumulated each step
  std::vector<double> radius;     // m
  std::vector<double> mass;       // kg
  std::vector<double> inertia;    // kg m^2 (sphere: 2/5 m r^2)
  std::vector<std::int32_t> material;
  std::vector<std::uint8_t> flags;
  std::vector<Index> id;  // stable id: survives reordering, used in output and events
  // The scene body the particle was generated in ([[body]] entries and stream copies in order,
  // 0 for the single [generator] form): kept through reordering, checkpoints and the output.
  std::vector<std::int32_t> body;

  std::size_t size() const { return position.size(); }

  // Appends a sphere at rest with identity orientation.
  Index add(const Vec3& x, double r, double density, std::int32_t material_id = 0, std::int32_t body_id = 0);
  void reserve(std::size_t n);
};

// Read-only pointers handed to plugins for one batch call.
struct ParticleView {
  std::size_t count = 0;
  const Vec3* position = nullptr;
  const Vec3* velocity = nullptr;
  const Quat* orientation = nullptr;
  const Vec3* omega = nullptr;
  const double* radius = nullptr;
  const double* mass = nullptr;
  const double* inertia = nullptr;
  const std::int32_t* material = nullptr;
  const Index* id = nullptr;
  const std::uint8_t* flags = nullptr;  // ParticleFlag bits
};

ParticleView view_of(const Particles& p);

// True when bond (i, j) may not fail: both its particles lie in an unbreakable zone.
inline bool bond_unbreakable(const ParticleView& p, Index i, Index j) {
  return p.flags != nullptr && (p.flags[i] & p.flags[j] & kUnbreakable) != 0;
}

}  // namespace shard
