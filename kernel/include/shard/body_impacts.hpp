#pragma once
// The first impact of every body of a scene (docs/reference/bodies.md, "Impacts"): when one of its spheres
// first touched a wall that does not carry it, the body's centre-of-mass velocity then and the
// wall's normal at the contact, from which the impact speed and angle follow. Read-only on the
// simulation: recording changes no result.
#include <cstdint>
#include <vector>

#include "shard/particles.hpp"
#include "shard/types.hpp"

namespace shard {

class Simulation;
struct Wall;

struct BodyImpact {
  bool hit = false;
  std::int64_t step = 0;         // the first step after which a sphere of the body touches a wall
  double time = 0;               // s
  Vec3 velocity = Vec3::Zero();  // m/s, the body's centre-of-mass velocity at the end of that step
  Vec3 normal = Vec3::Zero();    // unit, from the wall towards the touching sphere
  std::int32_t wall = -1;        // index of the wall in the scene's [[wall]] order

  double speed() const { return velocity.norm(); }
  // Angle between the velocity and the wall's inward normal -normal, degrees: 0 head-on, 90 grazing.
  double angle_degrees() const;
};

// A conveyor belt (a wall whose surface slides: surface_velocity or belt_speed) carries what lies
// on it: touching it is not an impact, so a plate riding a belt records the wall it falls onto.
bool carries_bodies(const Wall& wall);

// A checkpoint's flat numbers of the impacts (10 per body: hit, step, time, velocity, normal,
// wall), the same for the serial recorder and a decomposed run's; impacts_from_state throws
// std::invalid_argument when the count does not match `bodies`.
std::vector<double> impacts_state(const std::vector<BodyImpact>& impacts);
std::vector<BodyImpact> impacts_from_state(const std::vector<double>& state, std::size_t bodies);

class BodyImpactRecorder {
 public:
  // One record per body id 0..max(particles.body).
  explicit BodyImpactRecorder(const Particles& particles);

  // Call after every step. The impacts come from the kernel's own wall contacts
  // (Simulation::wall_contacts_begun): a step in which no body without an impact begins a contact
  // with a wall that does not carry it costs one look at each begun contact; a step with new
  // impacts one pass over the particles for the centre-of-mass velocities. The first call, and a
  // call that does not follow the step of the last one (a restart), scans every sphere against
  // every wall once instead, since the contacts begun earlier are not known.
  void update(const Simulation& simulation);

  const std::vector<BodyImpact>& impacts() const { return impacts_; }

  // Flat numbers for a checkpoint (10 per body) and back; restore throws std::invalid_argument
  // when the count does not match the bodies.
  std::vector<double> state() const;
  void restore(const std::vector<double>& state);

 private:
  // The contact that makes a body's impact: of the step's touching (wall, sphere) pairs the one
  // with the lowest wall index, then the lowest sphere id (its stable id: the particles' order,
  // renumbered at list rebuilds, or a decomposition over ranks does not change the choice).
  struct Candidate {
    std::int32_t wall = -1;
    Index particle = -1;  // the sphere's stable id
    Vec3 normal = Vec3::Zero();
  };
  void offer(std::size_t body, std::int32_t wall, Index particle, const Vec3& normal);
  void scan(const Simulation& simulation);
  void record(const Simulation& simulation);

  std::vector<BodyImpact> impacts_;
  std::size_t remaining_ = 0;
  std::int64_t last_step_ = -1;  // the step of the last update; -1: none since construction or restore
  // Per-body scratch, sized once: no allocation in the step loop.
  std::vector<Candidate> candidate_;
  std::vector<std::size_t> pending_;  // bodies with a candidate this step
  std::vector<Vec3> momentum_, centre_;
  std::vector<double> mass_, reach_;
  std::vector<char> near_;  // per body: its bounding sphere reaches the wall being scanned
};

}  // namespace shard
