// Reading run.h5 in the documented layout; writing labels and the fragment table back.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "run_file_fixture.hpp"
#include "shard/analysis/run_tables.hpp"

using namespace shard;
using namespace shard::analysis;

namespace {
std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("shard_test_run_file_" + name + ".h5");
}
const double kSphere = 4.0 / 3.0 * std::numbers::pi * 1e-9;  // volume of a 1 mm sphere, m^3
}  // namespace

TEST_CASE("frames, particles and bonds read as written; mass from the density attribute") {
  const auto path = scratch("read");
  test::write_run_file(path, test::breaking_bar(), 2500.0);
  const RunFile file(path);
  CHECK(file.frames() == std::vector<std::size_t>{0, 2});

  const FrameData f = file.read_frame(2);
  CHECK(f.step == 1000);
  CHECK(f.time == doctest::Approx(1e-4).scale(0));
  REQUIRE(f.id.size() == 6);
  CHECK(f.id[0] == 105);
  CHECK(f.position[0].x() == doctest::Approx(10e-3).scale(0));
  CHECK(f.velocity[0].y() == 1.0);
  CHECK(f.bond_i.size() == 4);
  CHECK(f.bond_i[0] == 5);  // bond 100-101: rows 5 and 4
  CHECK(f.bond_j[0] == 4);
  CHECK(f.body == std::vector<std::int32_t>(6, 0));  // no body dataset: one body
  for (double m : f.mass) CHECK(m == doctest::Approx(2500.0 * kSphere).epsilon(1e-14));

  const FragmentAnalysis a = analyse_fragments(particle_sample(f), bond_list(f));
  REQUIRE(a.fragments.size() == 2);
  // Equal masses (3 particles each): fragment 0 holds the smallest id, 100..102 (rows 3..5).
  CHECK(a.labels == std::vector<Index>{1, 1, 1, 0, 0, 0});
  CHECK(a.fragments[1].velocity.y() == doctest::Approx(1.0));
  std::filesystem::remove(path);
}

TEST_CASE("mass: the mass dataset wins; without density the reader asks for one") {
  auto frames = test::breaking_bar();
  frames[0].mass = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  const auto path = scratch("mass");
  test::write_run_file(path, frames, 0.0);
  const RunFile file(path);
  CHECK(file.read_frame(0).mass == std::vector<double>{1.0, 2.0, 3.0, 4.0, 5.0, 6.0});
  CHECK_THROWS_WITH_AS(file.read_frame(2), doctest::Contains("no mass dataset and the file no density attribute: "
                                                              "give the particle density (e.g. --density 2500"),
                       OutputError);
  const FrameData given = file.read_frame(2, 3000.0);
  CHECK(given.mass[3] == doctest::Approx(3000.0 * kSphere).epsilon(1e-14));
  CHECK_THROWS_AS(file.read_frame(1), OutputError);  // no such frame
  std::filesystem::remove(path);
}

TEST_CASE("an empty bond set reads as no bond: every particle its own fragment") {
  auto frames = test::breaking_bar();
  frames[1].bonds.clear();
  const auto path = scratch("empty");
  test::write_run_file(path, frames, 2500.0);
  const FrameData f = RunFile(path).read_frame(2);
  CHECK(f.bond_i.empty());
  CHECK(analyse_fragments(particle_sample(f), bond_list(f)).fragments.size() == 6);
  std::filesystem::remove(path);
}

TEST_CASE("labels and the fragment table are written back and read by HDF5") {
  const auto path = scratch("write");
  test::write_run_file(path, test::breaking_bar(), 2500.0);
  {
    RunFile file(path, RunFile::Mode::read_write);
    const FrameData f = file.read_frame(2);
    const FragmentAnalysis a = analyse_fragments(particle_sample(f), bond_list(f));
    file.write_fragment_labels(2, a.labels);
    write_fragment_table(file, 2, a.fragments, size_distribution(a.fragments));
    file.write_fragment_labels(2, a.labels);  // replacing must work too
  }
  const hid_t h = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(h >= 0);
  std::vector<std::int32_t> labels(6, -7);
  const hid_t set = H5Dopen2(h, "/frames/000002/fragment", H5P_DEFAULT);
  REQUIRE(set >= 0);
  H5Dread(set, H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, labels.data());
  H5Dclose(set);
  CHECK(labels == std::vector<std::int32_t>{1, 1, 1, 0, 0, 0});
  std::vector<double> d_eq(2, 0.0);
  const hid_t d = H5Dopen2(h, "/fragments/000002/d_eq", H5P_DEFAULT);
  REQUIRE(d >= 0);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d_eq.data());
  H5Dclose(d);
  // Three 1 mm spheres: d_eq = 2 mm * 3^(1/3).
  CHECK(d_eq[0] == doctest::Approx(2e-3 * std::cbrt(3.0)).epsilon(1e-12));
  double x50 = 0;
  const hid_t attr = H5Aopen_by_name(h, "/fragments/000002", "x50", H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(attr >= 0);
  H5Aread(attr, H5T_NATIVE_DOUBLE, &x50);
  H5Aclose(attr);
  CHECK(x50 == doctest::Approx(2e-3 * std::cbrt(3.0)).epsilon(1e-12));
  H5Fclose(h);
  std::filesystem::remove(path);
}

TEST_CASE("a frame cut off before its time attribute is not listed") {
  auto frames = test::breaking_bar();
  frames[1].complete = false;
  const auto path = scratch("partial");
  test::write_run_file(path, frames, 2500.0);
  CHECK(RunFile(path).frames() == std::vector<std::size_t>{0});
  // Asked for, it is named with what it lacks (docs/reference/errors.md, row 73).
  const std::string incomplete = "frame 2 of '" + path.string() + "' is incomplete (it lacks its step attribute)";
  CHECK_THROWS_WITH_AS(RunFile(path).read_frame(2), doctest::Contains(incomplete.c_str()), OutputError);
  std::filesystem::remove(path);
}

TEST_CASE("a missing or foreign file is reported by name") {
  CHECK_THROWS_AS(RunFile{scratch("does_not_exist")}, OutputError);
  const auto text = std::filesystem::temp_directory_path() / "shard_test_not_hdf5.h5";
  { std::ofstream(text) << "hello"; }
  CHECK_THROWS_AS(RunFile{text}, OutputError);
  std::filesystem::remove(text);
}
