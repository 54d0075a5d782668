#pragma once
// A 1 mm sphere on a horizontal plane wall under gravity, resting at its Hertz equilibrium overlap,
// launched along x at v0 (sliding without spin, or rolling: spin v0 / r about y), stepped by the
// kernel: the classic checks of friction laws against the rigid-body answer.
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

#include "shard/simulation.hpp"

namespace shard::effects_test {

struct SphereOnPlane {
  static constexpr double radius = 1e-3, density = 3720, g = 9.81, v0 = 0.05;
  double mass = 0;
  std::unique_ptr<Simulation> sim;

  // e_star: the law's Hertz modulus, for the equilibrium overlap (0: start touching, no overlap).
  SphereOnPlane(const ContactModel& model, double e_star, bool rolling = false) {
    Particles p;
    p.add(Vec3::Zero(), radius, density);
    mass = p.mass[0];
    // 4/3 E* sqrt(r) delta^1.5 = m g
    const double delta = e_star > 0 ? std::pow(3 * mass * g / (4 * e_star * std::sqrt(radius)), 2.0 / 3.0) : 0.0;
    p.position[0] = Vec3(0, 0, radius - delta);
    p.velocity[0] = Vec3(v0, 0, 0);
    // Rolling along +x on a floor below: the contact point (-r z) at rest, v + omega x (-r z) = 0.
    if (rolling) p.omega[0] = Vec3(0, v0 / radius, 0);
    SimulationSetup s;
    s.particles = std::move(p);
    s.contact = &model;
    Wall floor;
    floor.name = "floor";
    floor.shape = WallShape::Plane;
    floor.point = Vec3::Zero();
    floor.axis = Vec3::UnitZ();
    s.walls.push_back(floor);
    s.gravity = Vec3(0, 0, -g);
    sim = std::make_unique<Simulation>(std::move(s));
  }
  void run_to(double time) { sim->run(static_cast<std::int64_t>(std::llround((time - sim->time()) / sim->dt()))); }
  double velocity_at(double time) {
    run_to(time);
    return sim->particles().velocity[0].x();
  }
};

}  // namespace shard::effects_test
