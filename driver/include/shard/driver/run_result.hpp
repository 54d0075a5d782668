#pragma once
// What one run of a scene ended with, as the driver returns it: no log text to search.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "shard/analysis/load_curve.hpp"

namespace shard::driver {

enum class StopReason {
  Duration,         // reached the scene's duration
  LoadDrop,         // [stop] after_peak_fraction: the load fell below that fraction of its peak after breakage
  MaxDisplacement,  // [stop] max_displacement: the loading walls travelled that far
  Interrupted,      // SIGINT or SIGTERM (or a test's interrupt step): a checkpoint was written
  Observer,         // another observer asked the run to stop
  Rest,             // [stop] rest_speed, rest_time: every particle stayed slower than rest_speed for rest_time
};

struct RunResult {
  std::filesystem::path output;  // the run file
  std::int64_t steps = 0;
  double time = 0;  // s, simulated
  double dt = 0;
  std::size_t particles = 0;
  std::size_t bonds_initial = 0;  // at the start of the run (a restart counts bonds broken before it)
  std::int64_t bonds_broken = 0;
  // The load sensor's record (load_sensor.hpp), one row per series row; no id or uncertainties.
  analysis::LoadCurve curve;
  double peak_load = 0;             // N
  double displacement_at_peak = 0;  // m
  double final_displacement = 0;    // m
  // Kinetic energy less the rigid-body motion's (shard/analysis/deformation_kinetic.hpp) and
  // elastic (bond + contact) energy of the series rows before the first bond broke.
  std::vector<double> kinetic_before_break, elastic_before_break;
  // Quasi-static check: the largest kinetic / elastic energy ratio over the rows up to the peak
  // and before the first break whose load is at least 20 % of the run's peak load
  // (shard/analysis/quasi_static.hpp).
  double max_kinetic_to_elastic = 0;
  // Particle count of each fragment (connected set of bonded particles) at the last labelled
  // frame, largest first; empty when no frame was labelled (FragmentLabeller not composed).
  std::vector<std::size_t> fragment_particles;
  double wall_seconds = 0;
  StopReason stop = StopReason::Duration;
  std::string stop_reason;  // the same in words, for logs
  std::filesystem::path checkpoint;  // the last checkpoint written (empty: none)
  std::int64_t checkpoint_step = -1;
  std::int64_t restarted_from = -1;  // the checkpoint step a restart continued from
  int interrupt_signal = 0;  // the signal that interrupted the run (SIGINT for a test's interrupt step)
  bool interrupted() const { return stop == StopReason::Interrupted; }
};

}  // namespace shard::driver
