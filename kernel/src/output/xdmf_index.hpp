#pragma once
// The XDMF 2 index beside run.h5: a temporal collection whose every time step is a spatial
// collection of two grids over the same position dataset, the particles (Polyvertex) and the
// surviving bonds (Polyline, two nodes each). ParaView opens it as one time series.
#include <cstddef>
#include <filesystem>
#include <string>

namespace shard {

struct XdmfFrame {
  std::string group;  // "/frames/000003"
  double time = 0;    // s
  std::size_t particles = 0;
  std::size_t bonds = 0;
  bool fragments = false;
};

class XdmfIndex {
 public:
  // h5_name: how the .xmf refers to the data file, relative to the .xmf's folder.
  // Writes an index with no frames.
  XdmfIndex(std::filesystem::path xmf_path, std::string h5_name);

  // Adds a frame and rewrites the index atomically (temp file + rename), so a reader never
  // sees half a file. Throws OutputError when the folder is not writable.
  void add(const XdmfFrame& frame);
  const std::filesystem::path& path() const { return path_; }

 private:
  void write() const;

  std::filesystem::path path_;
  std::string h5_name_;
  std::string frames_xml_;  // rendered frames so far, appended once each
};

}  // namespace shard
