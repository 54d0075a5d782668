#pragma once
// Reads frames of a run.h5 (layout: docs/output-format.md) and writes the analysis results back
// into it: the per-particle "fragment" labels of a frame (ParaView colours by them) and the
// fragment table under /fragments/<k:06d>.
//
// Particle mass is taken, in this order, from
//   1. the frame's "mass" dataset (float64 [N], kg), if present;
//   2. m = rho 4/3 pi r^3 with rho = the caller's density override (e.g. `--density`);
//   3. ... with rho = the "density" attribute (kg/m^3) of the frame group, else of the file root.
//      A scalar applies to every particle; an array is indexed by the particle's material id.
// The parent body of each particle comes from the optional "body" dataset (int32 [N]); without
// it every particle belongs to body 0.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/analysis/body_statistics.hpp"
#include "shard/analysis/column_table.hpp"
#include "shard/analysis/components.hpp"
#include "shard/analysis/fragment_table.hpp"
#include "shard/analysis/size_distribution.hpp"
#include "shard/types.hpp"

namespace shard::analysis {

class RunFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Frame {
  std::int64_t index = 0;  // k of /frames/<k:06d>
  std::int64_t step = 0;
  double time = 0;         // s
  std::vector<Index> id;
  std::vector<Vec3> position, velocity;
  std::vector<double> radius, mass;
  std::vector<std::int32_t> material, body;  // body empty when the file has none
  std::vector<Index> bond_i, bond_j;         // surviving bonds, row indices
  std::string mass_source;                   // where the masses came from, for the report

  ParticleSample sample() const { return {id, position, velocity, radius, mass, body}; }
  BondList bonds() const { return {bond_i, bond_j}; }
};

class RunFile {
 public:
  enum class Mode { read, read_write };
  // Throws RunFileError naming the path if it is not a readable HDF5 file with a /frames group.
  explicit RunFile(const std::filesystem::path& path, Mode mode = Mode::read);
  ~RunFile();
  RunFile(const RunFile&) = delete;
  RunFile& operator=(const RunFile&) = delete;

  // Frame numbers k present under /frames, ascending; frames without their "time" attribute
  // (written last by the kernel) are incomplete and left out.
  std::vector<std::int64_t> frames() const;
  Frame read_frame(std::int64_t k, std::optional<double> density = std::nullopt) const;

  // Replaces the frame's "fragment" dataset (int32 [N]).
  void write_fragment_labels(std::int64_t k, const std::vector<Index>& labels);
  // Replaces /fragments/<k:06d>: one dataset per column of the table, the distribution's
  // characteristic sizes as attributes.
  void write_fragment_table(std::int64_t k, const std::vector<Fragment>& fragments,
                            const SizeDistribution& fsd);

  // Replaces /bodies/<k:06d>: one dataset per column of the per-body table, the run totals and
  // the pooled distribution as attributes.
  void write_body_table(std::int64_t k, const BodyReport& report);
  // /body_impacts written at the end of a run; empty when absent.
  std::vector<BodyImpactRow> read_body_impacts() const;
  // Replaces the group `group` (absolute; parents created) with the table (column_table.hpp).
  void write_table(const std::string& group, const ColumnTable& table);

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::int64_t file_ = -1;  // hid_t, kept out of the header so HDF5 stays a private dependency
};

std::string frame_name(std::int64_t k);  // "000012"

}  // namespace shard::analysis
