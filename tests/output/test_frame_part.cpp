// RunWriter::write_frame_part, the frame a run decomposed over MPI ranks writes from every rank at
// once (docs/explanation/scaling.md), in one process: a part holding every row reads back through RunFile
// exactly as write_frame's frame does, labels included; a part holding no row of an empty frame
// leaves a complete empty frame. (The several-process case: tests/mpi, test_mpi_run_parallel_frames.)
#include <doctest/doctest.h>

#include "run_fixtures.hpp"
#include "shard/run_file.hpp"

using namespace shard;
using namespace shard::test;

TEST_CASE("a frame written as one process's part reads back as write_frame's") {
  TempFolder dir("frame_part");
  const Particles p = make_particles(7, 2);
  const Bonds bonds = make_chain(7, 3);
  std::vector<Index> rows;  // the surviving bonds as row pairs, as the writer stores them
  for (std::size_t k = 0; k < bonds.size(); ++k)
    if (!bonds.broken[k]) rows.insert(rows.end(), {bonds.i[k], bonds.j[k]});
  const std::vector<Index> labels{0, 0, 0, 0, 1, 1, 1};
  {
    RunWriter whole(dir.path() / "whole.h5", RunMetadata{}, {});
    whole.write_frame(20, 0.5, p, bonds, &labels);
    RunWriter parts(dir.path() / "parts.h5", RunMetadata{}, {});
    FramePart part;
    part.particles = &p;
    part.total_rows = p.size();
    part.bond_rows = &rows;
    part.total_bonds = rows.size() / 2;
    part.fragment_labels = &labels;
    part.labelled = true;
    parts.write_frame_part(20, 0.5, part);
    FramePart none;  // an empty frame: no rows, no bonds, no labels
    const Particles nothing;
    none.particles = &nothing;
    parts.write_frame_part(21, 0.6, none);
  }
  const RunFile a(dir.path() / "parts.h5"), b(dir.path() / "whole.h5");
  REQUIRE(a.frame_count() == 2);
  const FrameData fa = a.read_frame(a.frames()[0]), fb = b.read_frame(b.frames()[0]);
  CHECK(fa.step == fb.step);
  CHECK(fa.time == fb.time);
  CHECK(fa.id == fb.id);
  CHECK(fa.position == fb.position);
  CHECK(fa.velocity == fb.velocity);
  CHECK(fa.omega == fb.omega);
  CHECK(fa.radius == fb.radius);
  CHECK(fa.mass == fb.mass);
  CHECK(fa.material == fb.material);
  CHECK(fa.body == fb.body);
  CHECK(fa.bond_i == fb.bond_i);
  CHECK(fa.bond_j == fb.bond_j);
  REQUIRE(fa.fragment.has_value());
  CHECK(*fa.fragment == labels);
  const FrameData empty = a.read_frame(a.frames()[1]);
  CHECK(empty.step == 21);
  CHECK(empty.id.empty());
  CHECK(empty.bond_i.empty());
  CHECK_FALSE(empty.fragment.has_value());
}
