#include "shard/particles.hpp"
#include "shard/particle_arrays.hpp"

#include <numbers>

namespace shard {

Index Particles::add(const Vec3& x, double r, double density, std::int32_t material_id, std::int32_t body_id) {
  const double m = density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const auto index = static_cast<Index>(size());
  position.push_back(x);
  velocity.push_back(Vec3::Zero());
  orientation.push_back(Quat::Identity());
  omega.push_back(Vec3::Zero());
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
  radius.push_back(r);
  mass.push_back(m);
  inertia.push_back(0.4 * m * r * r);
  material.push_back(material_id);
  flags.push_back(0);
  id.push_back(index);
  body.push_back(body_id);
  return index;
}

void Particles::reserve(std::size_t n) {
  for_each_particle_array([n](auto& v) { v.reserve(n); }, *this);
}

ParticleView view_of(const Particles& p) {
  ParticleView v;
  v.count = p.size();
  v.position = p.position.data();
  v.velocity = p.velocity.data();
  v.orientation = p.orientation.data();
  v.omega = p.omega.data();
  v.radius = p.radius.data();
  v.mass = p.mass.data();
  v.inertia = p.inertia.data();
  v.material = p.material.data();
  v.id = p.id.data();
  v.flags = p.flags.data();
  return v;
}

}  // namespace shard
