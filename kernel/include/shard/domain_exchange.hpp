#pragma once
// The two points of a step where a sub-domain of a decomposed run talks to its neighbours
// (docs/explanation/scaling.md). The kernel knows nothing of MPI: a Simulation given a DomainExchange
// calls it between the drift and the force pass, and after the pair and bond pass; the MPI build
// (mpi/) implements it. Without one (the default), a Simulation is the whole world.
#include <cstdint>

#include "shard/particles.hpp"

namespace shard {

// Particles::flags bit of a ghost: a copy of a particle another rank owns, kept so that pairs and
// bonds across the border can be computed. The neighbour list lists no pair whose end with the
// smaller stable id is a ghost: the rank owning that end computes the pair (owner-computes).
// Kernel-side only; plugins never see the flags.
inline constexpr std::uint8_t kGhost = 1u << 7;

class DomainExchange {
 public:
  virtual ~DomainExchange() = default;
  // Between the drift and the force pass: every ghost takes its owner's new position, velocity,
  // orientation and angular velocity.
  virtual void refresh_ghosts(Particles& particles) = 0;
  // After the pair and bond pass, before gravity and damping (damping is not linear in the force,
  // so it must see the whole force): the force and torque computed on each ghost are added to its
  // owner's particle, in a fixed order, and the ghost's are zeroed.
  virtual void return_reactions(Particles& particles) = 0;
};

}  // namespace shard
