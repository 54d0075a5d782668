#pragma once
// One HDF5 file per run (layout in docs/reference/output-format.md) and an XDMF index beside it so
// ParaView opens the run as a temporal collection. Every frame is flushed: a killed run leaves
// a readable file holding every frame written before the kill.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "shard/body_impacts.hpp"
#include "shard/bonds.hpp"
#include "shard/io/output_error.hpp"
#include "shard/particles.hpp"
#include "shard/wall.hpp"

namespace shard {

struct RunMetadata {
  std::string scene_text;     // the resolved scene (after --set overrides)
  std::string scene_file;
  std::uint64_t seed = 0;
  std::string shard_version;
  std::string git_revision;
  // (kind/name, "version=...; E=...; ...") for each loaded plugin
  std::vector<std::pair<std::string, std::string>> plugins;
  std::vector<std::pair<std::string, double>> generator_quality;
  std::vector<std::pair<std::string, std::string>> notes;  // e.g. time-step report
};

// One row of the time series.
struct SeriesRow {
  std::int64_t step = 0;
  double time = 0;
  double kinetic_energy = 0, bond_energy = 0, contact_energy = 0;
  std::int64_t bonds_intact = 0, bonds_broken = 0, contacts = 0;
  // Per wall, in the order of the walls vector: force, torque, displacement, the energy its
  // contacts dissipated and the impacts it received since the start (Wall).
  std::vector<Vec3> wall_force, wall_torque, wall_displacement;
  std::vector<double> wall_impact_energy;
  std::vector<std::int64_t> wall_impacts;

  // Appends the wall's columns (call once per wall, in order).
  void add_wall(const Wall& wall) {
    wall_force.push_back(wall.force);
    wall_torque.push_back(wall.torque);
    wall_displacement.push_back(wall.displacement);
    wall_impact_energy.push_back(wall.impact_energy());
    wall_impacts.push_back(wall.impacts);
  }
};

// How a RunWriter opens its file when several processes share it (a run decomposed over MPI
// ranks writing its frames in parallel: docs/explanation/scaling.md). The defaults are the serial writer.
struct RunWriterAccess {
  // Given the file-access property list (an hid_t) before the file is created: the MPI build
  // selects the MPI-IO driver here. Every call of the writer is then collective: each process
  // makes it with the same arguments (the frame parts aside).
  std::function<void(std::int64_t access)> configure;
  bool writes_index = true;  // this process keeps run.xmf (exactly one of those sharing the file)
};

// One process's rows of a frame written by several processes (RunWriter::write_frame_part). The
// fields the frame stores must be filled in `particles` (id, position, velocity, omega, radius,
// mass, material, body); the others may be empty.
struct FramePart {
  const Particles* particles = nullptr;
  std::size_t first_row = 0, total_rows = 0;  // where its rows go among all processes'
  // Its bonds as row pairs (i0 j0 i1 j1 ...) into the whole frame, at first_bond of total_bonds.
  const std::vector<Index>* bond_rows = nullptr;
  std::size_t first_bond = 0, total_bonds = 0;
  const std::vector<Index>* fragment_labels = nullptr;  // its rows' labels when `labelled`
  bool labelled = false;                                 // the same on every process
  // Given the dataset-transfer property list (an hid_t): the MPI build asks for collective I/O.
  std::function<void(std::int64_t transfer)> configure_transfer;
};

class RunWriter {
 public:
  // Creates (truncates) path; throws OutputError naming the path if it cannot be written.
  RunWriter(const std::filesystem::path& path, const RunMetadata& meta,
            const std::vector<std::string>& wall_names, const RunWriterAccess& access = {});
  ~RunWriter();
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  void append_series(const SeriesRow& row);
  void append_break_events(const std::vector<BondBreakEvent>& events);
  // A snapshot: particles, surviving bonds (as row-index pairs into this frame) and optional fragment labels.
  // Rewrites the .xmf index and flushes the file.
  void write_frame(std::int64_t step, double time, const Particles& particles, const Bonds& bonds,
                   const std::vector<Index>* fragment_labels = nullptr);
  // The same frame written by several processes at once (RunWriterAccess), each its own rows.
  void write_frame_part(std::int64_t step, double time, const FramePart& part);
  // /body_impacts (docs/reference/output-format.md): the first wall contact of every body. Once per run,
  // at its end (a frame's objects are never rewritten: see run_writer.cpp).
  void write_body_impacts(const std::vector<BodyImpact>& impacts);
  void flush();
  const std::filesystem::path& path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Whether run files may be written from several threads of one process at once: the HDF5
// library linked was built thread-safe. Debian's serial libhdf5 is; its MPI variant (the
// SHARD_WITH_MPI build's) is not, and two runs writing at once crash it in H5Dwrite.
bool run_files_thread_safe();

}  // namespace shard
