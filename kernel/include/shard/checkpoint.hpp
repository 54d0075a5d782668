#pragma once
// Everything a run needs to continue exactly where it stopped: a restarted run steps through the
// same floating-point operations in the same order as an uninterrupted one, so its final state
// is bit-identical. That means more than positions and velocities: the forces of the last step
// (the next half-kick uses them), the contact history and the neighbour list it is attached to
// (including where the list was built, which decides when it is rebuilt), the bonds' model state
// (reference frames), the break log, the walls' displacement, time and step.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "shard/bonds.hpp"
#include "shard/particles.hpp"
#include "shard/types.hpp"

namespace shard {

struct WallState {
  Vec3 velocity = Vec3::Zero();      // m/s
  Vec3 displacement = Vec3::Zero();  // m
  Vec3 force = Vec3::Zero();         // N, of the last step
  Vec3 torque = Vec3::Zero();        // N m
  double contact_work = 0;           // J, since the start (Wall::contact_work)
  double stored_energy = 0;          // J, in the wall's contacts at the last step
  std::int64_t impacts = 0;
  // m, where the wall stands at displacement zero: the scene's point, or where settling seated it.
  // NaN in a checkpoint written before walls could be seated: the scene's point then stands.
  Vec3 point = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
};

struct NeighbourState {
  double skin = 0;          // m
  std::size_t history_stride = 0;
  std::vector<Index> first, second;  // listed pairs; second < 0: wall -1 - second
  std::vector<double> history;       // history_stride per pair
  std::vector<Vec3> position_at_build;
  std::vector<Vec3> wall_displacement_at_build;
  std::vector<double> wall_angle_at_build;  // rad, per wall (zero unless it spins)
  std::vector<double> wall_reach;           // m, per wall (see NeighbourList)
  std::vector<std::uint8_t> touching;       // per pair: it touched at the last force pass
  std::int64_t rebuilds = 0;
};

struct SimulationState {
  std::int64_t step = 0;
  double time = 0;  // s
  double dt = 0;    // s
  Particles particles;
  Bonds bonds;
  std::int64_t bonds_broken = 0;
  std::vector<BondBreakEvent> events;
  std::size_t events_taken = 0;  // events already handed to the output
  std::vector<WallState> walls;
  NeighbourState neighbours;
  std::size_t contacts = 0;
  double contact_energy = 0;  // J
  double bond_energy = 0;     // J
};

// A checkpoint: the simulation state plus the run loop's own counters and load curve, stored as
// named numbers and named arrays so the application decides what it keeps.
struct Checkpoint {
  SimulationState simulation;
  std::vector<std::pair<std::string, double>> numbers;
  std::vector<std::pair<std::string, std::vector<double>>> arrays;

  double number(const std::string& name) const;  // throws CheckpointError when absent
  const std::vector<double>& array(const std::string& name) const;
};

class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// run.h5 -> run.checkpoint.h5, beside it.
std::filesystem::path checkpoint_path_for(const std::filesystem::path& run_file);

// Writes to a temporary file, flushes it to disk and renames it over `path`: a kill at any
// moment leaves either the previous checkpoint or the new one, never a torn one.
// Throws CheckpointError naming the path and the cause (disk full, read-only folder, ...).
void write_checkpoint(const std::filesystem::path& path, const Checkpoint& checkpoint);
// Where one process's rows of a table go in a checkpoint that several write at once.
struct CheckpointRows {
  std::size_t first = 0, total = 0;
};

// One process's share of a checkpoint that several write at once through one file (a run
// decomposed over MPI ranks: docs/explanation/scaling.md), in the serial layout.
// `checkpoint->simulation` holds this process's particles, bonds and touching contacts (their ends
// as rows of the whole file) for the rows given; everything else (the attributes, the break log,
// the walls, the loop's numbers and arrays) must be the same on every process and is written
// once, by the process with `writes_shared`.
struct CheckpointShare {
  const Checkpoint* checkpoint = nullptr;
  CheckpointRows particles, bonds, contacts;
  bool writes_shared = false;
  std::function<void(std::int64_t access)> configure;             // the file access list (the MPI-IO driver)
  std::function<void(std::int64_t transfer)> configure_transfer;  // each write's transfer list (collective)
};

// write_checkpoint's temporary file: `path` + ".tmp".
std::filesystem::path checkpoint_temporary_for(const std::filesystem::path& path);
// Collective over the processes sharing the file: writes `temporary` (checkpoint_temporary_for)
// and flushes it; publish_checkpoint, on one process once every one has returned, moves it into
// place. Throws CheckpointError naming the file and the cause.
void write_checkpoint_share(const std::filesystem::path& temporary, const CheckpointShare& share);
// The end of write_checkpoint: flushes `temporary` to disk and renames it over `path`; a kill
// before the rename leaves the previous checkpoint in place.
void publish_checkpoint(const std::filesystem::path& temporary, const std::filesystem::path& path);
// Throws CheckpointError naming the path when it is missing, unreadable or not a checkpoint.
Checkpoint read_checkpoint(const std::filesystem::path& path);

}  // namespace shard
