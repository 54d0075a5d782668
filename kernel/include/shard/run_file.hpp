#pragma once
// The one reader of a run file (layout in docs/reference/output-format.md): the metadata, the time series,
// the bond-break log and the frames, for `shard run --restart`, `shard bending`, `shard fragments`
// and the tests. Opens finished runs, running ones (what has been flushed when it is opened) and
// killed ones: a frame is listed only when all of it was flushed, and the series columns are cut
// to the rows every column holds. Opened for writing, it stores what the analysis adds: fragment
// labels in a frame and tables under a group (docs/reference/fragments.md).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "shard/bonds.hpp"
#include "shard/output.hpp"
#include "shard/types.hpp"

namespace shard {

struct FrameData {
  std::int64_t step = 0;
  double time = 0;  // s
  std::vector<Index> id;
  std::vector<Vec3> position;  // m
  std::vector<Vec3> velocity;  // m/s
  std::vector<Vec3> omega;     // rad/s
  std::vector<double> radius;  // m
  // kg: the frame's mass dataset, else rho 4/3 pi r^3 (RunFile::read_frame); mass_source says which.
  std::vector<double> mass;
  std::string mass_source;
  std::vector<std::int32_t> material;
  std::vector<std::int32_t> body;  // scene body of each particle (all 0 in files without the dataset)
  std::vector<Index> bond_i, bond_j;  // surviving bonds, row indices into this frame's arrays
  std::optional<std::vector<Index>> fragment;  // present when fragments were analysed
};

// A table stored under one group of an HDF5 file (a run file's, or a standalone one such as a
// sweep's): a dataset per column (all of one length; text as variable-length UTF-8) and the table's
// figures as attributes, in the order given.
struct RunTable {
  using Column = std::variant<std::vector<std::int32_t>, std::vector<std::int64_t>, std::vector<double>,
                              std::vector<Vec3>, std::vector<std::string>>;
  using Figure = std::variant<std::int64_t, double, std::string>;
  std::vector<std::pair<std::string, Column>> columns;
  std::vector<std::pair<std::string, Figure>> figures;
};

// Replaces `group` ("a/b" or "/a/b", parents created) of the HDF5 file `file` with the table; creates
// the file when it is absent. Throws OutputError naming the file.
void write_table_file(const std::filesystem::path& file, const std::string& group, const RunTable& table);

// "000012": the name of frame 12 under /frames.
std::string frame_name(std::size_t k);

class RunFile {
 public:
  enum class Mode { read, read_write };
  // Throws OutputError naming the path and the fix when it is missing, a folder, no HDF5 file, no
  // run file (no /frames group: a checkpoint?), of a newer format version than this Shard reads or,
  // for writing, cannot be opened for writing.
  explicit RunFile(const std::filesystem::path& path, Mode mode = Mode::read);
  static RunFile open(const std::filesystem::path& path) { return RunFile(path); }
  ~RunFile();
  RunFile(RunFile&&) noexcept;
  RunFile& operator=(RunFile&&) noexcept;
  RunFile(const RunFile&) = delete;
  RunFile& operator=(const RunFile&) = delete;

  const std::filesystem::path& path() const;

  // Root attributes and the /plugins, /generator and /notes groups.
  RunMetadata metadata() const;
  int abi_version() const;
  // The layout's version (root attribute format_version; 1 for files written before it existed).
  // Opening refuses a file newer than this Shard reads, naming both versions.
  int format_version() const;

  // The numbers k of the complete frames /frames/<k:06d>, ascending; a run of `shard run` numbers
  // them 0 .. frame_count() - 1. A frame is complete once it holds its step and time attributes and
  // every dataset of the layout (a kill may have torn the last one).
  const std::vector<std::size_t>& frames() const;
  std::size_t frame_count() const;
  // Frame k (a number of frames()). Masses: the frame's "mass" dataset when it has one, else
  // m = rho 4/3 pi r^3 with rho = `density` (kg/m^3) when given, else the "density" attribute of
  // the frame group or of the root (a number for every particle or a list indexed by material);
  // throws OutputError asking for the density when there is none of these.
  FrameData read_frame(std::size_t k, std::optional<double> density = std::nullopt) const;

  // Series rows held by every column.
  std::size_t series_rows() const;
  // "step", "time", "kinetic_energy", "bond_energy", "contact_energy", "bonds_intact",
  // "bonds_broken", "contacts" (integer columns converted exactly up to 2^53).
  std::vector<double> read_series(const std::string& name) const;
  std::vector<std::int64_t> read_integer_series(const std::string& name) const;
  std::vector<std::string> wall_names() const;
  // quantity: "force" (N), "torque" (N m) or "displacement" (m).
  std::vector<Vec3> read_wall_series(const std::string& wall, const std::string& quantity) const;
  // The energy the wall's contacts dissipated since the start (J) and the impacts it received;
  // throws OutputError for run files written before they were recorded.
  std::vector<double> read_wall_impact_energy(const std::string& wall) const;
  std::vector<std::int64_t> read_wall_impacts(const std::string& wall) const;

  std::vector<BondBreakEvent> read_break_events() const;
  // /body_impacts; empty when the run wrote none (killed, or older than the record).
  std::vector<BodyImpact> read_body_impacts() const;

  // Mode::read_write only. Replaces frame k's "fragment" dataset (one label per particle row).
  void write_fragment_labels(std::size_t k, const std::vector<Index>& labels);
  // Replaces the group `group` (e.g. "fragments/000012", parents created) with the table.
  void write_table(const std::string& group, const RunTable& table);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shard
