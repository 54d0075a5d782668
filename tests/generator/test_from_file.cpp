// from_file: a saved stl_fill packing reloads bit for bit; malformed files are refused by line.
#include <doctest/doctest.h>

#include <cstring>
#include <fstream>

#include "from_file.hpp"
#include "mesh_fixtures.hpp"
#include "stl_fill.hpp"

using namespace shard;

TEST_CASE("stl_fill save -> from_file reload is bit for bit, bonds and quality included") {
  const auto dir = test::scratch_dir("from_file_roundtrip");
  stl_fill::StlFillSettings s;
  s.file = test::geometry_dir() + "/cube_10mm.stl";
  s.scale = 0.001;
  s.diameter_min = 0.8e-3;
  s.diameter_max = 1.0e-3;
  s.save = (dir / "cube.csv").string();
  GeneratorContext context;
  context.seed = 2;
  const auto made = stl_fill::StlFill(s).generate(context);

  from_file::FromFileSettings f;
  f.spheres = "cube.csv";
  f.body = test::geometry_dir() + "/cube_10mm.stl";
  f.scale = 0.001;
  GeneratorContext reload;
  reload.scene_dir = dir.string();
  const auto loaded = from_file::FromFile(f).generate(reload);
  REQUIRE(loaded.position.size() == made.position.size());
  CHECK(std::memcmp(loaded.position.data(), made.position.data(), made.position.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(loaded.radius.data(), made.radius.data(), made.radius.size() * sizeof(double)) == 0);
  CHECK(loaded.bonds == made.bonds);
  auto figure = [](const GeneratedBody& b, const std::string& name) {
    for (const auto& [k, v] : b.quality)
      if (k == name) return v;
    return -1.0;
  };
  for (const char* name : {"solid_fraction", "coordination", "fabric_deviator"})
    CHECK(figure(loaded, name) == figure(made, name));
}

TEST_CASE("malformed sphere and bond files are refused with file, line and column") {
  const auto dir = test::scratch_dir("from_file_errors");
  std::ofstream(dir / "s.csv") << "x,y,z,r\n0,0,0,0.001\n0.002,0,0,0.001\n0.004,0,0,-1\n";
  from_file::FromFileSettings f;
  f.spheres = (dir / "s.csv").string();
  CHECK_THROWS_WITH(from_file::FromFile(f).generate({}), doctest::Contains("s.csv:4:11: spheres file: values must be finite and the radius > 0"));
  std::ofstream(dir / "ok.csv") << "x,y,z,r\n0,0,0,0.001\n0.002,0,0,0.001\n";
  std::ofstream(dir / "ok.bonds.csv") << "i,j\n0,2\n";
  f.spheres = (dir / "ok.csv").string();
  CHECK_THROWS_WITH(from_file::FromFile(f).generate({}), doctest::Contains("ok.bonds.csv:2:1: bonds file: not a bond; expected two different sphere indices"));
  std::ofstream(dir / "ok.bonds.csv") << "i,j\n0,1\n1,0\n";
  CHECK_THROWS_WITH(from_file::FromFile(f).generate({}), doctest::Contains("appears twice"));
  std::ofstream(dir / "overlap.csv") << "0,0,0,0.001\n0.0015,0,0,0.001\n";
  f.spheres = (dir / "overlap.csv").string();
  CHECK_THROWS_WITH(from_file::FromFile(f).generate({}), doctest::Contains("overlap by 0.5 of the smaller radius"));
  f.spheres = (dir / "none.csv").string();
  CHECK_THROWS_WITH(from_file::FromFile(f).generate({}), doctest::Contains("cannot be opened"));
}
