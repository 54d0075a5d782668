#pragma once
// The records a decomposed run moves between ranks as bytes (comm.hpp): a particle's whole state,
// a break event, a touching pair with its history; and the orders they are sorted in.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "shard/checkpoint.hpp"
#include "shard/particle_arrays.hpp"
#include "shard/particles.hpp"

namespace shard::mpi {

// One particle on its way to another rank: its whole state, so a migrated particle continues
// exactly (the force of the last step included: the next half-kick uses it).
struct ParticleRecord {
  double position[3], velocity[3], orientation[4], omega[3], force[3], torque[3];
  double radius, mass, inertia;
  std::int32_t material, body;
  Index id;
  std::int32_t owner;  // the rank owning it after the partition
  std::uint8_t flags;
};

inline ParticleRecord record_of(const Particles& p, std::size_t k) {
  ParticleRecord r{};
  std::copy_n(p.position[k].data(), 3, r.position);
  std::copy_n(p.velocity[k].data(), 3, r.velocity);
  std::copy_n(p.orientation[k].coeffs().data(), 4, r.orientation);
  std::copy_n(p.omega[k].data(), 3, r.omega);
  std::copy_n(p.force[k].data(), 3, r.force);
  std::copy_n(p.torque[k].data(), 3, r.torque);
  r.radius = p.radius[k];
  r.mass = p.mass[k];
  r.inertia = p.inertia[k];
  r.material = p.material[k];
  r.body = p.body[k];
  r.id = p.id[k];
  r.flags = static_cast<std::uint8_t>(p.flags[k] & ~kGhost);
  return r;
}

// Record `r` into slot k of `p` (a ghost copy with `ghost`).
inline void write(Particles& p, std::size_t k, const ParticleRecord& r, bool ghost) {
  p.position[k] = Vec3(r.position[0], r.position[1], r.position[2]);
  p.velocity[k] = Vec3(r.velocity[0], r.velocity[1], r.velocity[2]);
  std::copy_n(r.orientation, 4, p.orientation[k].coeffs().data());
  p.omega[k] = Vec3(r.omega[0], r.omega[1], r.omega[2]);
  p.force[k] = Vec3(r.force[0], r.force[1], r.force[2]);
  p.torque[k] = Vec3(r.torque[0], r.torque[1], r.torque[2]);
  p.radius[k] = r.radius;
  p.mass[k] = r.mass;
  p.inertia[k] = r.inertia;
  p.material[k] = r.material;
  p.body[k] = r.body;
  p.id[k] = r.id;
  p.flags[k] = ghost ? static_cast<std::uint8_t>(r.flags | kGhost) : r.flags;
}

// Every per-particle array of `p` to n entries (new ones to be written).
inline void resize(Particles& p, std::size_t n) {
  for_each_particle_array([n](auto& v) { v.resize(n); }, p);
}

inline void append(Particles& p, const ParticleRecord& r, bool ghost) {
  const std::size_t k = p.size();
  resize(p, k + 1);
  write(p, k, r, ghost);
}

// A break event as plain numbers, for the gather.
struct EventRecord {
  std::int64_t step;
  double time;
  Index id_i, id_j;  // id_i < id_j
  double midpoint[3];
  BondStress stress;
};

inline bool event_order(const EventRecord& a, const EventRecord& b) {
  if (a.step != b.step) return a.step < b.step;
  if (a.id_i != b.id_i) return a.id_i < b.id_i;
  return a.id_j < b.id_j;
}

inline bool by_id(const ParticleRecord& a, const ParticleRecord& b) { return a.id < b.id; }

// The touching pairs of a rank's list as records (first id, second id or -1 - wall, history):
// a pair's history travels with it, matched again by ids wherever it lands.
inline void append_touching(const SimulationState& s, std::vector<double>& out) {
  const Particles& p = s.particles;
  const NeighbourState& list = s.neighbours;
  for (std::size_t k = 0; k < list.first.size(); ++k) {
    if (!list.touching[k]) continue;  // a pair that does not touch has no history to carry
    const Index b = list.second[k];
    out.push_back(static_cast<double>(p.id[static_cast<std::size_t>(list.first[k])]));
    out.push_back(b < 0 ? static_cast<double>(b) : static_cast<double>(p.id[static_cast<std::size_t>(b)]));
    out.insert(out.end(), list.history.begin() + static_cast<std::ptrdiff_t>(k * list.history_stride),
               list.history.begin() + static_cast<std::ptrdiff_t>((k + 1) * list.history_stride));
  }
}

// Record k of a flat array of records of `width` doubles, ordered by their first two numbers.
inline std::vector<std::size_t> record_order(const std::vector<double>& flat, std::size_t width) {
  std::vector<std::size_t> order(width > 0 ? flat.size() / width : 0);
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double* x = flat.data() + a * width;
    const double* y = flat.data() + b * width;
    return x[0] != y[0] ? x[0] < y[0] : x[1] < y[1];
  });
  return order;
}

}  // namespace shard::mpi
