// run.h5's format_version: written by the run writer, read back by RunFile; a file without the
// attribute (written before it existed) reads as version 1; a newer version is refused, by RunFile
// and by the from_file generator alike, since both open run files through shard::h5.
#include <doctest/doctest.h>
#include <hdf5.h>

#include <cstdint>
#include <string>

#include "run_fixtures.hpp"
#include "shard/run_file.hpp"

using namespace shard;

namespace {

void write_small_run(const std::filesystem::path& file) {
  RunWriter writer(file, test::make_metadata(), {});
  writer.write_frame(0, 0.0, test::make_particles(4, 0), test::make_chain(4, 4));
}

// Replaces (or with version < 0 removes) the root attribute, as another writer would have left it.
void set_format_version(const std::filesystem::path& file, std::int64_t version) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(f >= 0);
  if (H5Aexists(f, "format_version") > 0) H5Adelete(f, "format_version");
  if (version >= 0) {
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(f, "format_version", H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, H5T_NATIVE_INT64, &version);
    H5Aclose(attribute);
    H5Sclose(space);
  }
  H5Fclose(f);
}

std::string open_error(const std::filesystem::path& file) {
  try {
    RunFile run(file);
  } catch (const OutputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("the run writer stamps format_version 1 and RunFile reads it") {
  test::TempFolder dir("format_version");
  const auto file = dir.path() / "run.h5";
  write_small_run(file);
  CHECK(RunFile(file).format_version() == 1);
  CHECK(RunFile(file).frame_count() == 1);
}

TEST_CASE("a run file without format_version is read as version 1") {
  test::TempFolder dir("format_version_absent");
  const auto file = dir.path() / "run.h5";
  write_small_run(file);
  set_format_version(file, -1);
  const RunFile run(file);
  CHECK(run.format_version() == 1);
  CHECK(run.read_frame(0).radius.size() == 4);
}

TEST_CASE("a run file of a newer format version is refused with both versions named") {
  test::TempFolder dir("format_version_newer");
  const auto file = dir.path() / "run.h5";
  write_small_run(file);
  set_format_version(file, 2);
  std::string expected = "'";
  expected.append(file.string());
  expected.append("' is a run file of format version 2, but this Shard reads format versions 1 to 1; read it with "
                  "the newer Shard that wrote it (its shard_version attribute names it)");
  CHECK(open_error(file) == expected);
  set_format_version(file, 0);
  CHECK(open_error(file).find("format version 0") != std::string::npos);
}
