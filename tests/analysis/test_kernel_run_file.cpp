// The reader against the kernel's own writer (shard::RunWriter): the layout both follow is
// docs/reference/output-format.md, and this test fails if either drifts from it.
#include <doctest/doctest.h>

#include <filesystem>

#include "shard/analysis/fragment_table.hpp"
#include "shard/analysis/run_tables.hpp"
#include "shard/bonds.hpp"
#include "shard/output.hpp"
#include "shard/particles.hpp"

using namespace shard;
using namespace shard::analysis;

TEST_CASE("a frame written by RunWriter reads back: ids, state, bonds, fragments") {
  const auto dir = std::filesystem::temp_directory_path() / "shard_test_kernel_run_file";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const double rho = 2650.0;
  Particles p;
  for (int k = 0; k < 5; ++k) p.add(Vec3(1e-3 * k, 0.0, 0.0), 0.5e-3 * (1 + k % 2), rho, k % 2);
  p.id = {40, 30, 20, 10, 0};  // stable ids differ from rows, as after a reordering
  p.velocity[4] = Vec3(0.0, 0.0, -3.0);
  Bonds bonds;
  bonds.i = {0, 1, 3};
  bonds.j = {1, 2, 4};
  {
    RunWriter writer(dir / "run.h5", RunMetadata{}, {});
    writer.write_frame(0, 0.0, p, Bonds{});
    writer.write_frame(250, 2.5e-6, p, bonds);
  }
  const RunFile file(dir / "run.h5");
  REQUIRE(file.frames() == std::vector<std::size_t>{0, 1});
  const FrameData f = file.read_frame(1, rho);
  CHECK(f.step == 250);
  CHECK(f.time == doctest::Approx(2.5e-6).scale(0));
  CHECK(f.id == p.id);
  CHECK(f.material == p.material);
  CHECK(f.velocity[4].z() == -3.0);
  CHECK(f.bond_i == bonds.i);
  CHECK(f.bond_j == bonds.j);
  for (std::size_t k = 0; k < 5; ++k) {
    CHECK(f.position[k].x() == p.position[k].x());
    CHECK(f.mass[k] == doctest::Approx(p.mass[k]).epsilon(1e-14));  // same formula, same rho
  }
  const FragmentAnalysis a = analyse_fragments(particle_sample(f), bond_list(f));
  REQUIRE(a.fragments.size() == 2);
  CHECK(a.labels == std::vector<Index>{0, 0, 0, 1, 1});
  CHECK(a.fragments[0].mass == doctest::Approx(p.mass[0] + p.mass[1] + p.mass[2]).epsilon(1e-14));
  CHECK(file.read_frame(0, rho).bond_i.empty());
  std::filesystem::remove_all(dir);
}
