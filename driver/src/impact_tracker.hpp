#pragma once
// The first wall impact of every body (shard/body_impacts.hpp, docs/reference/bodies.md) over a run backend
// (run_backend.hpp), serial or decomposed: each rank offers the wall contacts its own spheres
// began, the offers of all ranks are gathered in rank order and one rule picks each body's contact
// alike on every rank (the lowest wall index, then the lowest sphere id), and the body's
// centre-of-mass velocity is summed over the ranks in rank order. Every rank holds the same table;
// state() is BodyImpactRecorder's, so checkpoints continue in either build.
#include <cstdint>
#include <vector>

#include "shard/body_impacts.hpp"
#include "run_backend.hpp"
#include "whole_scene.hpp"

namespace shard::driver::detail {

class ImpactTracker {
 public:
  // One record per body of the whole scene (the same on every rank).
  explicit ImpactTracker(const BodyCount& bodies);

  // Collective; call after every step. A step in which no rank began a wall contact sends nothing
  // (the count travels with the step's own reduction); a step in which some did, one all-gather of
  // the offers (few) and, when a body got its impact, one sum of the new impacts' momenta. The
  // first call, and a call that does not follow the step of the last one (a restart), scans every
  // rank's own spheres against every wall instead, since the contacts begun earlier are not known.
  void update(const RunBackend& run);

  const std::vector<BodyImpact>& impacts() const { return impacts_; }
  std::vector<double> state() const { return impacts_state(impacts_); }
  void restore(const std::vector<double>& state);

 private:
  void offer(std::size_t body, std::int32_t wall, Index id, const Vec3& normal);
  void scan(const RunBackend& run, std::vector<double>& offers) const;
  void record(const RunBackend& run);

  struct Candidate {
    std::int32_t wall = -1;
    Index id = -1;  // the sphere's stable id
    Vec3 normal = Vec3::Zero();
  };
  std::vector<BodyImpact> impacts_;
  bool bodies_known_ = false;  // the particles carry body ids
  std::size_t remaining_ = 0;
  std::int64_t last_step_ = -1;
  std::vector<Candidate> candidate_;
  std::vector<std::size_t> pending_;  // bodies with a candidate this step, in the order offered
  std::vector<std::size_t> slot_;     // per body: its place in pending_ while recording
};

}  // namespace shard::driver::detail
