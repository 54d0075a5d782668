#pragma once
// Where a run's simulation lives: whole in this process (serial_backend.cpp) or decomposed in space
// over the MPI ranks of the job (mpi/mpi_backend.cpp). The run loop (run_scene.cpp), the
// numerical-health watch and the impact tracker are written once over this interface: each figure
// they read is the whole run's, made from this process's share by the backend's reductions, which
// are identities in a serial run.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shard/checkpoint.hpp"
#include "shard/driver/run_observer.hpp"
#include "shard/output.hpp"
#include "shard/scene.hpp"
#include "shard/simulation.hpp"
#include "whole_scene.hpp"

namespace shard::driver::detail {

// A wall contact begun in the last step on one of this process's own particles, named by stable
// id and body (a decomposed run renumbers its local particles at a re-partition).
struct WallContactBegun {
  Index id = 0;
  std::int32_t body = 0;
  std::int32_t wall = 0;
  Vec3 normal = Vec3::Zero();  // unit, from the wall towards the particle
};

class RunBackend {
 public:
  virtual ~RunBackend() = default;

  // --- Before the simulation exists.
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // The checkpoint a restart continues from (a decomposed run also needs the particles' ids).
  virtual Checkpoint read_restart(const std::filesystem::path& checkpoint) const = 0;
  // Runs `work` on rank 0 only / on every rank; a failure reaches every rank alike.
  virtual void on_root(const std::function<void()>& work) const = 0;
  virtual void on_all(const std::function<void()>& work) const = 0;
  // Waits for every rank.
  virtual void barrier() const = 0;
  // How the run file is opened (every rank of a decomposed run holds it open through MPI-IO).
  virtual RunWriterAccess run_file_access() const = 0;
  // This process's part of the scene, instantiated: the whole scene where it is generated (once
  // per run), the models alone elsewhere; and the whole scene's figures on every process. A
  // failure to instantiate reaches every rank alike.
  virtual ScenePart instantiate(const Scene& scene, const PluginHost& host,
                                const std::function<void(const std::string&)>& log) const = 0;
  // Builds this process's simulation from its part of the scene (`part.instance.simulation`,
  // released here), or from the checkpoint `from`. Throws std::invalid_argument for a state it
  // cannot hold.
  virtual void start(const Scene& scene, ScenePart& part, const SimulationState* from) = 0;
  // The run's notes for the run file and its log ("" serially).
  virtual void add_notes(RunMetadata& meta, bool restarting) const = 0;
  virtual std::string where() const = 0;  // ", over N MPI ranks"

  // --- This process's share; local() steps only through step().
  virtual Simulation& local() = 0;
  const Simulation& local() const { return const_cast<RunBackend*>(this)->local(); }
  virtual bool owns(std::size_t k) const = 0;
  virtual void step() = 0;
  virtual const std::vector<WallContactBegun>& wall_contacts_begun() const = 0;
  // What observers read of the whole run, or null when local() is the whole run.
  virtual const RunState::Whole* whole() const = 0;

  // --- The whole run's figures; collective.
  virtual Energies energies() const = 0;
  virtual std::size_t bond_count() = 0;  // intact bonds
  virtual std::int64_t bonds_broken() const = 0;
  virtual std::size_t contact_count() const = 0;
  virtual std::int64_t wall_contacts_begun_anywhere() const = 0;
  // The break events since the last call (the run file takes them).
  virtual std::vector<BondBreakEvent> take_new_break_events() = 0;
  // Writes `loop` (the run loop's numbers and arrays, the same on every rank) with the whole
  // simulation state as the checkpoint `file`, crash-safe (write_checkpoint). Collective.
  virtual void write_checkpoint(Checkpoint& loop, const std::filesystem::path& file) const = 0;
  // analysis::deformation_kinetic_energy of the whole run's particles.
  virtual double deformation_kinetic_energy() const = 0;
  // Writes a frame of the whole run; `before_frame` lets the observers label it.
  virtual void write_frame(RunWriter& writer, RunState& state, const std::function<void()>& before_frame) = 0;

  // --- Reductions over the ranks, in rank order (the same on every rank).
  virtual std::vector<double> sum_over_ranks(const std::vector<double>& mine) const = 0;
  virtual std::vector<double> gather_over_ranks(const std::vector<double>& mine) const = 0;
  virtual bool any_rank(bool mine) const = 0;
};

}  // namespace shard::driver::detail
