#pragma once
// Reads a run file written by RunWriter (layout in docs/output-format.md): the metadata, the
// time series, the bond-break log and the frames. Opens finished runs, running ones (what has
// been flushed when it is opened) and killed ones: a frame is listed only when all of it was
// flushed, and the series columns are cut to the rows every column holds.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
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
  std::vector<std::int32_t> material;
  std::vector<std::int32_t> body;  // scene body of each particle (all 0 in files without the dataset)
  std::vector<std::array<Index, 2>> bonds;  // row indices into this frame's arrays
  std::optional<std::vector<Index>> fragment;  // present when fragments were analysed
};

class RunFile {
 public:
  // Throws OutputError naming the path when it is missing or not a Shard run file.
  explicit RunFile(const std::filesystem::path& path);
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

  std::size_t frame_count() const;
  FrameData read_frame(std::size_t k) const;

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

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shard
