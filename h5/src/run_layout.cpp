#include "run_layout.hpp"

#include <fmt/format.h>

#include "h5_io.hpp"
#include "shard/io/output_error.hpp"

namespace shard::h5 {
namespace {

void check_is_hdf5(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code error;
  if (!std::filesystem::exists(path, error))
    throw OutputError(name + ": no such run file (it does not exist); give the run.h5 that `shard run` wrote");
  if (std::filesystem::is_directory(path, error))
    throw OutputError(name + ": is a folder, not a run file; give the run.h5 inside it");
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw OutputError("'" + name + "' is not an HDF5 file, so not a run file; give the run.h5 that `shard run` wrote");
  }
}

hid_t open_id(const std::filesystem::path& path, RunAccess access) {
  if (access == RunAccess::read_write) return H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  // A running job holds an exclusive lock on its file; reading what it has flushed is the point
  // of flushing, so a locked file is opened again without locking. (Not the first choice:
  // within the writer's own process HDF5 refuses a second open with other locking flags.)
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id >= 0) return id;
  H5Eclear2(H5E_DEFAULT);
  Handle list = plist_handle(H5Pcreate(H5P_FILE_ACCESS), "creating file access list");
  check(H5Pset_file_locking(list.get(), false, true), "disabling file locking");
  return H5Fopen(path.c_str(), H5F_ACC_RDONLY, list.get());
}

void check_format_version(hid_t file, const std::string& name) {
  const std::int64_t version = run_format_version(file);
  if (version < 1 || version > kRunFormatVersion)
    throw OutputError(fmt::format("'{}' is a run file of format version {}, but this Shard reads format versions 1 "
                                  "to {}; {}",
                                  name, version, kRunFormatVersion,
                                  version > kRunFormatVersion ? "read it with the newer Shard that wrote it (its "
                                                                "shard_version attribute names it)"
                                                              : "the attribute is damaged; write the run again"));
}

}  // namespace

Handle open_run_file(const std::filesystem::path& path, RunAccess access) {
  check_is_hdf5(path);
  const std::string name = path.string();
  const hid_t id = open_id(path, access);
  if (id < 0) {
    const std::string cause = take_error_stack();
    const std::string detail = cause.empty() ? "" : " (" + cause + ")";
    if (access == RunAccess::read_write)
      throw OutputError(fmt::format("cannot open the run file '{}' for writing{}; is it read-only, or is its run "
                                    "still going?",
                                    name, detail));
    throw OutputError(fmt::format("cannot open the run file '{}'{}; it is damaged: give the run.h5 that `shard run` "
                                  "wrote",
                                  name, detail));
  }
  Handle file(id, H5Fclose);
  if (!path_exists(file.get(), "frames"))
    throw OutputError(name + ": has no /frames group, so it is no Shard run file (a checkpoint?); give the run.h5 "
                             "that `shard run` wrote");
  check_format_version(file.get(), name);
  return file;
}

std::int64_t run_format_version(hid_t file) {
  return has_attribute(file, "format_version") ? read_int_attribute(file, "format_version") : 1;
}

void write_run_format_version(hid_t file) { write_attribute(file, "format_version", kRunFormatVersion); }

std::string frame_path(std::size_t k) { return fmt::format("frames/{:06d}", k); }

std::string frame_missing_part(hid_t group) {
  for (const char* name : {"step", "time"})
    if (!has_attribute(group, name)) return fmt::format("its {} attribute", name);
  for (const char* name : {"id", "position", "velocity", "omega", "radius", "material", "bonds"})
    if (!path_exists(group, name)) return fmt::format("its '{}' dataset", name);
  return {};
}

bool frame_complete(hid_t group) {
  try {
    return frame_missing_part(group).empty();
  } catch (const OutputError&) {
    return false;
  }
}

}  // namespace shard::h5
