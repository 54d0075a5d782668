// Simulation::export_state / import_state: the whole mutable state of a run, so a restart
// continues with the same floating-point operations in the same order (see checkpoint.hpp).
#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "neighbour_list.hpp"
#include "shard/checkpoint.hpp"
#include "shard/simulation.hpp"

namespace shard {
namespace {

void require_consistent(const Particles& p) {
  const std::size_t n = p.size();
  const bool ok = p.velocity.size() == n && p.orientation.size() == n && p.omega.size() == n &&
                  p.force.size() == n && p.torque.size() == n && p.radius.size() == n && p.mass.size() == n &&
                  p.inertia.size() == n && p.material.size() == n && p.flags.size() == n && p.id.size() == n &&
                  p.body.size() == n;
  if (!ok) throw std::invalid_argument("the checkpoint's particle arrays have different lengths");
}

void require_consistent(const Bonds& b, std::size_t particles, std::size_t stride) {
  const std::size_t m = b.size();
  if (b.stride != stride)
    throw std::invalid_argument(fmt::format(
        "the checkpoint's bonds carry {} state values each, the bond model {}: restart with the bond model the "
        "run was started with",
        b.stride, stride));
  const std::size_t loads = b.keeps_loads ? m : 0;
  const bool ok = b.j.size() == m && b.state.size() == m * stride && b.force.size() == loads &&
                  b.torque_i.size() == loads && b.torque_j.size() == loads && b.energy.size() == loads &&
                  b.broken.size() == m && b.stress.size() == m;
  if (!ok) throw std::invalid_argument("the checkpoint's bond arrays have different lengths");
  for (std::size_t k = 0; k < m; ++k)
    if (b.i[k] < 0 || b.j[k] < 0 || static_cast<std::size_t>(b.i[k]) >= particles ||
        static_cast<std::size_t>(b.j[k]) >= particles)
      throw std::invalid_argument(fmt::format("the checkpoint's bond {} names a particle that does not exist", k));
}

}  // namespace

SimulationState Simulation::state_without_arrays() const {
  SimulationState s;
  s.step = step_;
  s.time = time_;
  s.dt = dt_;
  s.bonds_broken = bonds_broken_;
  s.events_taken = events_taken_;
  s.walls.reserve(walls_.size());
  for (const Wall& w : walls_)
    s.walls.push_back({w.velocity, w.displacement, w.force, w.torque, w.contact_work, w.stored_energy, w.impacts, w.point});
  s.contacts = contacts_;
  s.contact_energy = contact_energy_;
  s.bond_energy = bond_energy_;
  return s;
}

SimulationState Simulation::export_state() const {
  SimulationState s = state_without_arrays();
  s.particles = particles_;
  s.bonds = bonds_;
  s.events = events_;
  s.neighbours = neighbours_->state();
  return s;
}

SimulationState Simulation::take_state() {
  SimulationState s = state_without_arrays();
  s.particles = std::move(particles_);
  s.bonds = std::move(bonds_);
  s.events = std::move(events_);
  s.neighbours = neighbours_->take_state();
  // Emptied explicitly (a moved-from vector's size is unspecified); the bonds keep their layout.
  particles_ = Particles{};
  Bonds none;
  none.stride = s.bonds.stride;
  none.keeps_loads = s.bonds.keeps_loads;
  bonds_ = std::move(none);
  events_.clear();
  return s;
}

void Simulation::import_state(const SimulationState& s) { import_state(SimulationState(s)); }

void Simulation::import_state(SimulationState&& s) {
  require_consistent(s.particles);
  require_consistent(s.bonds, s.particles.size(), bonds_.stride);
  if (s.walls.size() != walls_.size())
    throw std::invalid_argument(fmt::format("the checkpoint has {} walls, the scene {}: restart with the scene the run "
                                            "was started with",
                                            s.walls.size(), walls_.size()));
  if (s.events_taken > s.events.size())
    throw std::invalid_argument("the checkpoint's break log is shorter than the part already written");
  if (!(s.dt > 0)) throw std::invalid_argument("the checkpoint's time step is not positive");
  // With several materials each particle's index picks a row of the contact law's table.
  if (materials_ > 1)
    for (std::size_t k = 0; k < s.particles.size(); ++k)
      if (s.particles.material[k] < 0 || s.particles.material[k] >= materials_)
        throw std::invalid_argument(fmt::format("the checkpoint's particle {} has material {}, but the scene has "
                                                "materials 0 to {}: restart with the scene the run was started with",
                                                s.particles.id[k], s.particles.material[k], materials_ - 1));
  // Everything is checked before anything is replaced: a refused checkpoint leaves this intact.
  neighbours_->restore(std::move(s.neighbours));
  step_ = s.step;
  time_ = s.time;
  dt_ = s.dt;
  particles_ = std::move(s.particles);
  // The loads are outputs of the last step, not inputs of the next: this run keeps them or not
  // whatever the run that wrote the checkpoint did.
  const bool keeps_loads = bonds_.keeps_loads;
  bonds_ = std::move(s.bonds);
  if (bonds_.keeps_loads != keeps_loads) bonds_.set_keeps_loads(keeps_loads);
  bonds_broken_ = s.bonds_broken;
  events_ = std::move(s.events);
  events_taken_ = s.events_taken;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    walls_[w].velocity = s.walls[w].velocity;
    walls_[w].displacement = s.walls[w].displacement;
    walls_[w].force = s.walls[w].force;
    walls_[w].torque = s.walls[w].torque;
    walls_[w].contact_work = s.walls[w].contact_work;
    walls_[w].stored_energy = s.walls[w].stored_energy;
    walls_[w].impacts = s.walls[w].impacts;
    if (s.walls[w].point.allFinite()) walls_[w].point = s.walls[w].point;
    place_wall(walls_[w], time_);  // the rotation is a function of time, not kept
  }
  contacts_ = s.contacts;
  contact_energy_ = s.contact_energy;
  bond_energy_ = s.bond_energy;
}

}  // namespace shard
