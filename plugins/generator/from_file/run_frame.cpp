#include "run_frame.hpp"

#include <fmt/core.h>
#include <hdf5.h>

#include <array>
#include <stdexcept>
#include <string>

#include "shard/hdf5_quiet.hpp"

namespace shard::from_file {

namespace {

// Owns one HDF5 identifier; closes it with the function matching its kind.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};


bool link_exists(hid_t parent, const std::string& path) {
  // Each path component must exist before the next is asked for.
  std::size_t from = 0;
  while (true) {
    const std::size_t slash = path.find('/', from);
    const std::string head = path.substr(0, slash);
    if (H5Lexists(parent, head.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
    from = slash + 1;
  }
}

std::string frame_name(std::size_t k) { return fmt::format("frames/{:06d}", k); }

// A frame counts when its group holds step, time and every per-particle dataset (a killed run
// may have torn its last frame); the same rule as shard::RunFile.
bool frame_complete(hid_t group) {
  if (H5Aexists(group, "step") <= 0 || H5Aexists(group, "time") <= 0) return false;
  for (const char* name : {"id", "position", "velocity", "omega", "radius", "material", "bonds"})
    if (H5Lexists(group, name, H5P_DEFAULT) <= 0) return false;
  return true;
}

// /frame_index holds the object address of frame k (0 = none); it survives a kill that tears
// the /frames link index, so frames are located through it first, then by name.
std::vector<haddr_t> frame_addresses(hid_t file) {
  std::vector<haddr_t> addresses;
  if (!link_exists(file, "frame_index")) return addresses;
  Handle set(H5Dopen2(file, "frame_index", H5P_DEFAULT), H5Dclose);
  Handle space(set.valid() ? H5Dget_space(set.get()) : -1, H5Sclose);
  if (!space.valid() || H5Sget_simple_extent_ndims(space.get()) != 1) return addresses;
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  std::vector<std::uint64_t> entries(static_cast<std::size_t>(n));
  if (n == 0 || H5Dread(set.get(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, entries.data()) < 0)
    return addresses;
  for (std::uint64_t entry : entries) {
    if (entry == 0) break;
    addresses.push_back(static_cast<haddr_t>(entry));
  }
  return addresses;
}

Handle open_frame(hid_t file, const std::vector<haddr_t>& addresses, std::size_t k) {
  if (k < addresses.size()) return Handle(H5Oopen_by_addr(file, addresses[k]), H5Oclose);
  if (!link_exists(file, frame_name(k))) return Handle(-1, H5Oclose);
  return Handle(H5Oopen(file, frame_name(k).c_str(), H5P_DEFAULT), H5Oclose);
}

std::size_t count_frames(hid_t file, const std::vector<haddr_t>& addresses) {
  std::size_t k = 0;
  while (true) {
    const Handle group = open_frame(file, addresses, k);
    if (!group.valid() || !frame_complete(group.get())) return k;
    ++k;
  }
}

template <typename T>
hid_t memory_type();
template <>
hid_t memory_type<double>() { return H5T_NATIVE_DOUBLE; }
template <>
hid_t memory_type<std::int32_t>() { return H5T_NATIVE_INT32; }
template <>
hid_t memory_type<std::int64_t>() { return H5T_NATIVE_INT64; }

// Reads dataset `name` of `group` as rows x cols values (cols 0: one-dimensional).
template <typename T>
std::vector<T> read_dataset(hid_t group, const char* name, std::size_t cols, std::size_t& rows,
                            const std::string& where) {
  Handle set(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  if (!set.valid()) throw std::runtime_error(fmt::format("{}: cannot open dataset '{}'", where, name));
  Handle space(H5Dget_space(set.get()), H5Sclose);
  const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  std::array<hsize_t, 2> dims{0, 0};
  if (rank != (cols == 0 ? 1 : 2) || H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0 ||
      (cols != 0 && dims[1] != cols))
    throw std::runtime_error(fmt::format("{}: dataset '{}' does not have the shape [n{}] of the run-file layout",
                                         where, name, cols == 0 ? "" : fmt::format(",{}", cols)));
  rows = static_cast<std::size_t>(dims[0]);
  std::vector<T> values(rows * (cols == 0 ? 1 : cols));
  if (!values.empty() && H5Dread(set.get(), memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw std::runtime_error(fmt::format("{}: cannot read dataset '{}'", where, name));
  return values;
}

template <typename T>
T read_scalar_attribute(hid_t group, const char* name, const std::string& where) {
  Handle attribute(H5Aopen(group, name, H5P_DEFAULT), H5Aclose);
  T value{};
  if (!attribute.valid() || H5Aread(attribute.get(), memory_type<T>(), &value) < 0)
    throw std::runtime_error(fmt::format("{}: cannot read attribute '{}'", where, name));
  return value;
}

}  // namespace

RunFrame read_run_frame(const std::filesystem::path& path, long frame) {
  const QuietHdf5Errors quiet;  // failures here become exceptions instead
  const std::string file_name = path.string();
  if (!std::filesystem::exists(path)) throw std::runtime_error(fmt::format("run file '{}' does not exist", file_name));
  if (H5Fis_hdf5(file_name.c_str()) <= 0)
    throw std::runtime_error(fmt::format("'{}' is not an HDF5 file (expected a Shard run.h5)", file_name));
  Handle file(H5Fopen(file_name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) throw std::runtime_error(fmt::format("cannot open the run file '{}'", file_name));
  if (H5Aexists(file.get(), "abi_version") <= 0 || !link_exists(file.get(), "frames"))
    throw std::runtime_error(fmt::format("'{}' is an HDF5 file but not a Shard run file", file_name));

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
  const Handle group = open_frame(file.get(), addresses, out.index);
  out.step = read_scalar_attribute<std::int64_t>(group.get(), "step", where);
  out.time = read_scalar_attribute<double>(group.get(), "time", where);

  std::size_t n = 0, rows = 0;
  const auto xyz = read_dataset<double>(group.get(), "position", 3, n, where);
  out.radius = read_dataset<double>(group.get(), "radius", 0, rows, where);
  if (rows != n) throw std::runtime_error(fmt::format("{}: {} radii for {} positions", where, rows, n));
  out.material = read_dataset<std::int32_t>(group.get(), "material", 0, rows, where);
  if (rows != n) throw std::runtime_error(fmt::format("{}: {} materials for {} positions", where, rows, n));
  const auto pairs = read_dataset<std::int32_t>(group.get(), "bonds", 2, rows, where);

  out.position.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.position[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  out.bonds.resize(rows);
  for (std::size_t b = 0; b < rows; ++b) {
    const Index i = pairs[2 * b], j = pairs[2 * b + 1];
    if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n || static_cast<std::size_t>(j) >= n || i == j)
      throw std::runtime_error(fmt::format("{}: bond {} joins rows {} and {} of {} particles", where, b, i, j, n));
    out.bonds[b] = {i, j};
  }
  return out;
}

}  // namespace shard::from_file
