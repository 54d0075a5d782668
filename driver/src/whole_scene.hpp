#pragma once
// What a run reads of the whole scene as instantiated, on every process: a few numbers and names,
// made where the whole scene is (the one process of a serial run, rank 0 of a decomposed one) and
// handed to the others (mpi/mpi_backend.cpp), which hold none of its particles before the first
// partition sends them their share.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "shard/scene.hpp"
#include "shard/simulation.hpp"

namespace shard::driver::detail {

// How many bodies the particles belong to (the largest body id + 1), and whether they carry body
// ids at all: the first-impact table's size (impact_tracker.hpp).
struct BodyCount {
  std::size_t bodies = 0;
  bool known = false;
};
BodyCount body_count(const Particles& whole);

struct WholeScene {
  std::size_t particles = 0;
  double dt = 0;                                        // s, as the whole scene's Simulation chose it
  std::vector<TimeStepLimit> limits;                    // the models' over the whole scene
  std::vector<std::pair<std::string, double>> quality;  // the packing's (SceneInstance::body)
  BodyCount bodies;
  // The energy watch's baseline (health_watch.hpp): kinetic + bond + contact and gravitational
  // energy at the start, J, and the scale a first gain is judged against, J.
  double energy0 = 0, potential0 = 0, energy_scale = 0;
};
// From `inst`, which holds the whole scene's Simulation.
WholeScene whole_scene_of(const SceneInstance& inst);

// This process's part of the scene as instantiated (the whole scene where it was generated, the
// models alone elsewhere) and the whole scene's figures, the same on every process.
struct ScenePart {
  SceneInstance instance;
  WholeScene whole;
};

}  // namespace shard::driver::detail
