#include "run_frame.hpp"

#include <fmt/core.h>

#include <stdexcept>
#include <string>

#include "h5_io.hpp"
#include "run_layout.hpp"

namespace shard::from_file {

namespace {

// Frame k: through /frame_index first (it survives a kill that tears the /frames link index),
// then by name; an invalid handle when absent.
h5::Handle open_frame(hid_t file, const std::vector<haddr_t>& addresses, std::size_t k) {
  if (k < addresses.size()) return h5::Handle(H5Oopen_by_addr(file, addresses[k]), H5Oclose);
  if (!h5::path_exists(file, h5::frame_path(k))) return {};
  return h5::Handle(H5Oopen(file, h5::frame_path(k).c_str(), H5P_DEFAULT), H5Oclose);
}

std::size_t count_frames(hid_t file, const std::vector<haddr_t>& addresses) {
  std::size_t k = 0;
  while (true) {
    const h5::Handle group = open_frame(file, addresses, k);
    if (!group || !h5::frame_complete(group.get())) return k;
    ++k;
  }
}

std::vector<haddr_t> frame_addresses(hid_t file) {
  try {
    return h5::read_frame_addresses(file);
  } catch (const OutputError&) {
    return {};  // a damaged index: the frames are found by name
  }
}

void read_particles(hid_t group, RunFrame& out, const std::string& where) {
  const auto xyz = h5::read_dataset<double>(group, "position", 3);
  const std::size_t n = xyz.size() / 3;
  out.radius = h5::read_dataset<double>(group, "radius", 0);
  if (out.radius.size() != n)
    throw std::runtime_error(fmt::format("{}: {} radii for {} positions", where, out.radius.size(), n));
  out.material = h5::read_dataset<std::int32_t>(group, "material", 0);
  if (out.material.size() != n)
    throw std::runtime_error(fmt::format("{}: {} materials for {} positions", where, out.material.size(), n));
  out.position.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.position[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
}

void read_bonds(hid_t group, RunFrame& out, const std::string& where) {
  const auto pairs = h5::read_dataset<std::int32_t>(group, "bonds", 2);
  const std::size_t n = out.position.size();
  out.bonds.resize(pairs.size() / 2);
  for (std::size_t b = 0; b < out.bonds.size(); ++b) {
    const Index i = pairs[2 * b], j = pairs[2 * b + 1];
    if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n || static_cast<std::size_t>(j) >= n || i == j)
      throw std::runtime_error(fmt::format("{}: bond {} joins rows {} and {} of {} particles", where, b, i, j, n));
    out.bonds[b] = {i, j};
  }
}

}  // namespace

// Opened, versioned and checked for complete frames by the run-file layer the kernel's RunFile
// uses too (run_layout.hpp).
RunFrame read_run_frame(const std::filesystem::path& path, long frame) {
  const h5::QuietErrors quiet;  // failures here become exceptions instead
  const std::string file_name = path.string();
  const h5::Handle file = h5::open_run_file(path, h5::RunAccess::read);
  const std::vector<haddr_t> addresses = frame_addresses(file.get());
  RunFrame out;
  out.frame_count = count_frames(file.get(), addresses);
  const long count = static_cast<long>(out.frame_count);
  const long k = frame < 0 ? count + frame : frame;
  if (k < 0 || k >= count)
    throw std::runtime_error(fmt::format("run file '{}' holds {} complete frame(s); frame {} does not exist "
                                         "(0 ... {}, or -1 for the last)",
                                         file_name, count, frame, count - 1));
  out.index = static_cast<std::size_t>(k);
  const std::string where = fmt::format("run file '{}', frame {}", file_name, out.index);
  const h5::Handle group = open_frame(file.get(), addresses, out.index);
  try {
    out.step = h5::read_int_attribute(group.get(), "step");
    out.time = h5::read_double_attribute(group.get(), "time");
    read_particles(group.get(), out, where);
    read_bonds(group.get(), out, where);
  } catch (const OutputError& e) {
    throw std::runtime_error(fmt::format("{}: {}", where, e.what()));
  }
  return out;
}

}  // namespace shard::from_file
