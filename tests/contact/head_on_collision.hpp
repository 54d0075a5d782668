#pragma once
// A two-body head-on collision along x, integrated with the kernel's velocity-Verlet scheme
// (half kick, drift, force from the half-step velocity, half kick), calling the model each step.
#include <cstddef>
#include <stdexcept>

#include "contact_arrays.hpp"
#include "shard/contact_model.hpp"

namespace shard::test {

struct Sphere {
  double mass;    // kg
  double radius;  // m
};

struct CollisionResult {
  double restitution = 0;  // separation speed / approach speed
  double max_overlap = 0;  // m
  std::size_t steps_in_contact = 0;
};

// Particle i (moving in -x) hits j (moving in +x) or, without j, a fixed plane wall at x = 0,
// at relative speed v0. The centre of mass is at rest, so the pair leaves along x as well.
inline CollisionResult head_on_collision(const ContactModel& model, const Sphere& a, const Sphere* b, double v0,
                                         double dt) {
  const bool wall = b == nullptr;
  const double m_j = wall ? 0.0 : b->mass;
  const double r_j = wall ? 0.0 : b->radius;
  const double m_eff = wall ? a.mass : a.mass * m_j / (a.mass + m_j);
  const double r_eff = wall ? a.radius : a.radius * r_j / (a.radius + r_j);
  double x_i = a.radius + r_j;  // just touching
  double x_j = 0.0;
  double v_i = wall ? -v0 : -v0 * m_j / (a.mass + m_j);
  double v_j = wall ? 0.0 : v0 * a.mass / (a.mass + m_j);
  double f = 0.0;  // force on i along x

  ContactArrays contact(1, model.history_size());
  contact.j[0] = wall ? -1 : 1;
  contact.r_eff[0] = r_eff;
  contact.m_eff[0] = m_eff;
  CollisionResult result;
  const std::size_t max_steps = 100'000'000;
  for (std::size_t step = 0; step < max_steps; ++step) {
    v_i += 0.5 * dt * f / a.mass;
    if (!wall) v_j -= 0.5 * dt * f / m_j;
    x_i += dt * v_i;
    x_j += dt * v_j;
    const double overlap = a.radius + r_j - (x_i - x_j);
    if (overlap <= 0.0) {
      f = 0.0;
      if (result.steps_in_contact > 0) {
        result.restitution = (v_i - v_j) / v0;  // no force: these are the final velocities
        return result;
      }
      continue;
    }
    ++result.steps_in_contact;
    result.max_overlap = std::max(result.max_overlap, overlap);
    contact.overlap[0] = overlap;
    contact.velocity[0] = Vec3(v_i - v_j, 0.0, 0.0);
    ContactBatch batch = contact.batch(dt);
    model.compute(batch);
    f = contact.force[0].x();
    v_i += 0.5 * dt * f / a.mass;
    if (!wall) v_j -= 0.5 * dt * f / m_j;
  }
  throw std::runtime_error("head_on_collision: the particles never separated");
}

}  // namespace shard::test
