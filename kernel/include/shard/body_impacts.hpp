#pragma once
// The first wall contact of every body of a scene (docs/bodies.md, "Impacts"): when it happened,
// the body's centre-of-mass velocity then and the wall's normal at the contact, from which the
// impact speed and angle follow. Read-only on the simulation: recording changes no result.
#include <cstdint>
#include <vector>

#include "shard/particles.hpp"
#include "shard/types.hpp"

namespace shard {

class Simulation;

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

class BodyImpactRecorder {
 public:
  // One record per body id 0..max(particles.body).
  explicit BodyImpactRecorder(const Particles& particles);

  // Call after every step. Bodies already hit cost nothing; the others cost one pass over their
  // spheres for the centre of mass and bounding radius, one wall test per body and wall, and a
  // test of every sphere only for bodies whose bounding sphere reaches the wall.
  void update(const Simulation& simulation);

  const std::vector<BodyImpact>& impacts() const { return impacts_; }

  // Flat numbers for a checkpoint (10 per body) and back; restore throws std::invalid_argument
  // when the count does not match the bodies.
  std::vector<double> state() const;
  void restore(const std::vector<double>& state);

 private:
  std::vector<BodyImpact> impacts_;
  std::size_t remaining_ = 0;
  // Per-body scratch, sized once: no allocation in the step loop.
  std::vector<Vec3> momentum_, centre_;
  std::vector<double> mass_, reach_;
  std::vector<char> near_;  // per body: its bounding sphere reaches the wall being tested
};

}  // namespace shard
