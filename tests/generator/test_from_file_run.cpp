// from_file reading a Shard run file: a packing written frame by frame with the kernel's
// RunWriter must come back from from_file's own HDF5 reader bit for bit (positions, radii,
// materials, surviving bonds), for the chosen frame.
#include <doctest/doctest.h>
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <utility>
#include <vector>

#include "from_file.hpp"
#include "mesh_fixtures.hpp"
#include "shard/output.hpp"
#include "stl_fill.hpp"

using namespace shard;

namespace {

// One written frame: the particles and the bonds that survive in it.
struct WrittenFrame {
  Particles particles;
  std::vector<std::pair<Index, Index>> surviving;
};

// Frame k of a small "run" of the filled cube: frame 0 as generated; frame 1 translated by an
// irrational-looking offset with every third bond broken (broken bonds are not in a frame);
// frame 2 rotated about z by 0.1 rad, materials alternating. Rigid motions keep the packing
// free of overlaps, so from_file's overlap check passes.
WrittenFrame make_frame(const GeneratedBody& body, int k, Bonds& bonds) {
  WrittenFrame out;
  const Eigen::AngleAxisd rotation(0.1, Vec3::UnitZ());
  const Vec3 offset(1.0e-3 / 3.0, -std::sqrt(2.0) * 1e-4, 0.7e-3 / 7.0);
  for (std::size_t i = 0; i < body.radius.size(); ++i) {
    Vec3 x = body.position[i];
    if (k == 1) x += offset;
    if (k == 2) x = rotation * x;
    out.particles.add(x, body.radius[i], 2500.0, k == 2 ? static_cast<std::int32_t>(i % 2) : 0);
  }
  bonds.resize(body.bonds.size());
  for (std::size_t b = 0; b < body.bonds.size(); ++b) {
    bonds.i[b] = body.bonds[b].first;
    bonds.j[b] = body.bonds[b].second;
    bonds.broken[b] = (k >= 1 && b % 3 == 0) ? 1 : 0;
    if (bonds.broken[b] == 0) out.surviving.push_back(body.bonds[b]);
  }
  return out;
}

GeneratedBody load(const std::filesystem::path& run, long frame) {
  from_file::FromFileSettings f;
  f.run = run.string();
  f.frame = frame;
  return from_file::FromFile(f).generate({});
}

void check_same(const GeneratedBody& loaded, const WrittenFrame& written) {
  const Particles& p = written.particles;
  REQUIRE(loaded.position.size() == p.size());
  CHECK(std::memcmp(loaded.position.data(), p.position.data(), p.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(loaded.radius.data(), p.radius.data(), p.size() * sizeof(double)) == 0);
  CHECK(loaded.material == p.material);
  CHECK(loaded.bonds == written.surviving);
}

}  // namespace

TEST_CASE("from_file loads a run.h5 frame written by RunWriter exactly") {
  const auto dir = test::scratch_dir("from_file_run");
  stl_fill::StlFillSettings s;
  s.file = test::geometry_dir() + "/cube_10mm.stl";
  s.scale = 0.001;
  s.diameter_min = 0.8e-3;
  s.diameter_max = 1.0e-3;
  GeneratorContext context;
  context.seed = 3;
  const GeneratedBody body = stl_fill::StlFill(s).generate(context);
  REQUIRE(body.radius.size() > 500);

  const auto run = dir / "run.h5";
  std::vector<WrittenFrame> written;
  {
    RunMetadata meta;
    meta.scene_text = "# test";
    meta.seed = 3;
    RunWriter writer(run, meta, {});
    for (int k = 0; k < 3; ++k) {
      Bonds bonds;
      written.push_back(make_frame(body, k, bonds));
      writer.write_frame(100 * k, 1e-5 * k, written.back().particles, bonds);
    }
  }
  // Each frame differs from the others, so loading the wrong one cannot pass.
  REQUIRE(written[1].surviving.size() < written[0].surviving.size());

  check_same(load(run, -1), written[2]);  // default: the last frame
  check_same(load(run, 2), written[2]);
  check_same(load(run, 1), written[1]);
  check_same(load(run, 0), written[0]);
  check_same(load(run, -3), written[0]);

  // Frame 0 is the generated body itself: the coordination figure is reproduced.
  const auto figure = [](const GeneratedBody& b, const std::string& name) {
    for (const auto& [key, value] : b.quality)
      if (key == name) return value;
    return -1.0;
  };
  CHECK(figure(load(run, 0), "coordination") == figure(body, "coordination"));
  CHECK(figure(load(run, 1), "coordination") < figure(body, "coordination"));
}

TEST_CASE("from_file refuses a missing frame, a non-run file and an ambiguous source") {
  const auto dir = test::scratch_dir("from_file_run_errors");
  const auto run = dir / "run.h5";
  {
    Particles p;
    p.add(Vec3::Zero(), 1e-3, 2500.0);
    p.add(Vec3(2e-3, 0, 0), 1e-3, 2500.0);
    Bonds bonds;
    bonds.resize(1);
    bonds.i[0] = 0;
    bonds.j[0] = 1;
    RunWriter writer(run, RunMetadata{}, {});
    writer.write_frame(0, 0.0, p, bonds);
  }
  CHECK(load(run, 0).bonds.size() == 1);
  CHECK_THROWS_WITH(load(run, 1), doctest::Contains("holds 1 complete frame(s); frame 1 does not exist"));
  CHECK_THROWS_WITH(load(run, -2), doctest::Contains("frame -2 does not exist"));
  std::ofstream(dir / "text.h5") << "not hdf5\n";
  CHECK_THROWS_WITH(load(dir / "text.h5", -1), doctest::Contains("is not an HDF5 file"));
  CHECK_THROWS_WITH(load(dir / "none.h5", -1), doctest::Contains("does not exist"));
  from_file::FromFileSettings both;
  both.run = run.string();
  both.spheres = "x.csv";
  CHECK_THROWS_WITH(from_file::FromFile(both).generate({}), doctest::Contains("exactly one of 'spheres'"));
  both.spheres.clear();
  both.run.clear();
  CHECK_THROWS_WITH(from_file::FromFile(both).generate({}), doctest::Contains("exactly one of 'spheres'"));
}

TEST_CASE("from_file refuses a run file of a newer format version, as RunFile does") {
  const auto dir = test::scratch_dir("from_file_run_version");
  const auto run = dir / "run.h5";
  {
    Particles p;
    p.add(Vec3::Zero(), 1e-3, 2500.0);
    RunWriter writer(run, RunMetadata{}, {});
    writer.write_frame(0, 0.0, p, Bonds{});
  }
  CHECK(load(run, 0).position.size() == 1);
  const hid_t f = H5Fopen(run.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t attribute = H5Aopen(f, "format_version", H5P_DEFAULT);
  REQUIRE(attribute >= 0);  // the writer stamped it
  const std::int64_t newer = 2;
  H5Awrite(attribute, H5T_NATIVE_INT64, &newer);
  H5Aclose(attribute);
  H5Fclose(f);
  CHECK_THROWS_WITH(load(run, 0), doctest::Contains("is a run file of format version 2, but this Shard reads format "
                                                    "versions 1 to 1"));
}
