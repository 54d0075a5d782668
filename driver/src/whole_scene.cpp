#include "whole_scene.hpp"

#include <algorithm>
#include <cmath>

namespace shard::driver::detail {
namespace {

// The energy scale a gain is judged against at the start: the larger of |energy0| and the
// round-off floor. A body at rest holds only round-off energy (1e-30 J), whose growth is no
// blow-up; the kinetic energy of every particle moving 1e-6 of its radius per step is negligible
// physics, and a real instability passes it within a few steps.
double initial_scale(const Simulation& whole, double energy0) {
  double round_off_floor = 0;
  const Particles& p = whole.particles();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double v = 1e-6 * p.radius[k] / whole.dt();
    round_off_floor += 0.5 * p.mass[k] * v * v;
  }
  return std::max(std::abs(energy0), round_off_floor);
}

}  // namespace

BodyCount body_count(const Particles& whole) {
  std::int32_t top = -1;
  for (std::int32_t b : whole.body) top = std::max(top, b);
  return {static_cast<std::size_t>(top + 1), whole.body.size() == whole.size()};
}

WholeScene whole_scene_of(const SceneInstance& inst) {
  const Simulation& sim = *inst.simulation;
  WholeScene w;
  w.particles = sim.particles().size();
  w.dt = sim.dt();
  w.limits = sim.time_step_limits();
  w.quality = inst.body.quality;
  w.bodies = body_count(sim.particles());
  const Energies e = sim.energies();
  w.energy0 = e.kinetic + e.bond + e.contact;
  w.potential0 = e.gravity;
  w.energy_scale = initial_scale(sim, w.energy0);
  return w;
}

}  // namespace shard::driver::detail
