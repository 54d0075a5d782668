#pragma once
// Every per-particle array of Particles, in one place: code that must treat all of them alike
// (reserve, reorder, migrate) visits them here, so a new field cannot be left out of one of them.
#include "shard/particles.hpp"

namespace shard {

// Calls f(a.field, b.field, ...) for each per-particle array of the given Particles, field by field.
template <class F, class... P>
void for_each_particle_array(F&& f, P&... p) {
  f(p.position...);
  f(p.velocity...);
  f(p.orientation...);
  f(p.omega...);
  f(p.force...);
  f(p.torque...);
  f(p.radius...);
  f(p.mass...);
  f(p.inertia...);
  f(p.material...);
  f(p.flags...);
  f(p.id...);
  f(p.body...);
}

}  // namespace shard
