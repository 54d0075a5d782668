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
// wall), the same for a serial and a decomposed run (the run driver's impact tracker records
// them); impacts_from_state throws std::invalid_argument when the count does not match `bodies`.
std::vector<double> impacts_state(const std::vector<BodyImpact>& impacts);
std::vector<BodyImpact> impacts_from_state(const std::vector<double>& state, std::size_t bodies);

}  // namespace shard
