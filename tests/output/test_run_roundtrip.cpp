// A small run written with RunWriter and read back with RunFile: every value must come back
// bit for bit (HDF5 stores float64 and the integer widths we write, no conversion).
#include <doctest/doctest.h>

#include "run_fixtures.hpp"
#include "shard/plugin.hpp"
#include "shard/run_file.hpp"

using namespace shard;
using namespace shard::test;

namespace {

const std::vector<std::string> kWalls{"top", "bottom"};
constexpr std::size_t kParticles = 6;
constexpr std::int64_t kRowsPerFrame = 50;  // 3 frames: 150 rows, beyond two 64-row blocks
constexpr std::int64_t kEventsPerFrame = 25;

void check_frame(const FrameData& f, int frame, bool fragments) {
  const Particles p = make_particles(kParticles, frame);
  CHECK(f.step == 1000 * frame);
  CHECK(f.time == frame * 1e-4 / 3.0);
  CHECK(f.id == p.id);
  CHECK(f.position == p.position);
  CHECK(f.velocity == p.velocity);
  CHECK(f.omega == p.omega);
  CHECK(f.radius == p.radius);
  CHECK(f.material == p.material);
  CHECK(f.body == p.body);
  // The chain minus the bond flagged broken, as row pairs in the original order.
  std::vector<Index> expected_i, expected_j;
  for (Index k = 0; k + 1 < static_cast<Index>(kParticles); ++k)
    if (k != frame) expected_i.push_back(k), expected_j.push_back(k + 1);
  CHECK(f.bond_i == expected_i);
  CHECK(f.bond_j == expected_j);
  CHECK(f.mass == p.mass);
  REQUIRE(f.fragment.has_value() == fragments);
  if (fragments) {
    std::vector<Index> labels;
    for (std::size_t k = 0; k < kParticles; ++k) labels.push_back(k <= 2 ? 0 : 1);
    CHECK(*f.fragment == labels);
  }
}

}  // namespace

TEST_CASE("a run written by RunWriter reads back exactly with RunFile") {
  TempFolder folder("roundtrip");
  const auto path = folder.path() / "nested" / "run.h5";  // the writer creates the folder
  const RunMetadata meta = make_metadata();
  std::vector<Index> labels;
  for (std::size_t k = 0; k < kParticles; ++k) labels.push_back(k <= 2 ? 0 : 1);
  {
    RunWriter writer(path, meta, kWalls);
    CHECK(writer.path() == path);
    std::int64_t row = 0, event = 0;
    for (int frame = 0; frame < 3; ++frame) {
      for (std::int64_t r = 0; r < kRowsPerFrame; ++r) writer.append_series(make_row(row++, 2));
      // Events arrive in uneven batches, as a step loop delivers them.
      std::vector<BondBreakEvent> batch;
      for (std::int64_t e = 0; e < kEventsPerFrame; ++e) {
        batch.push_back(make_event(event++));
        if (e % 7 == 6) {
          writer.append_break_events(batch);
          batch.clear();
        }
      }
      writer.append_break_events(batch);
      const Particles p = make_particles(kParticles, frame);
      const Bonds b = make_chain(kParticles, static_cast<std::size_t>(frame));
      writer.write_frame(1000 * frame, frame * 1e-4 / 3.0, p, b, frame == 2 ? &labels : nullptr);

      // A running job's file is readable up to its last frame, series and events included.
      const RunFile running(path);
      CHECK(running.frame_count() == static_cast<std::size_t>(frame + 1));
      CHECK(running.series_rows() == static_cast<std::size_t>(row));
      CHECK(running.read_break_events().size() == static_cast<std::size_t>(event));
      check_frame(running.read_frame(static_cast<std::size_t>(frame)), frame, frame == 2);
    }
    // Rows after the last frame reach the file through the destructor's flush.
    for (int r = 0; r < 3; ++r) writer.append_series(make_row(row++, 2));
  }

  const RunFile run(path);
  SUBCASE("metadata") {
    const RunMetadata m = run.metadata();
    CHECK(m.scene_text == meta.scene_text);
    CHECK(m.scene_file == meta.scene_file);
    CHECK(m.seed == meta.seed);
    CHECK(m.shard_version == meta.shard_version);
    CHECK(m.git_revision == meta.git_revision);
    CHECK(m.plugins == meta.plugins);  // in the order written
    CHECK(m.generator_quality == meta.generator_quality);
    CHECK(m.notes == meta.notes);
    CHECK(run.abi_version() == kAbiVersion);
  }
  SUBCASE("frames") {
    REQUIRE(run.frame_count() == 3);
    for (int frame = 0; frame < 3; ++frame)
      check_frame(run.read_frame(static_cast<std::size_t>(frame)), frame, frame == 2);
    CHECK_THROWS_AS(run.read_frame(3), OutputError);
  }
  SUBCASE("series") {
    const std::size_t rows = 3 * kRowsPerFrame + 3;
    REQUIRE(run.series_rows() == rows);
    const auto step = run.read_integer_series("step");
    const auto time = run.read_series("time");
    const auto kinetic = run.read_series("kinetic_energy");
    const auto bond = run.read_series("bond_energy");
    const auto contact = run.read_series("contact_energy");
    const auto intact = run.read_integer_series("bonds_intact");
    const auto broken = run.read_integer_series("bonds_broken");
    const auto contacts = run.read_series("contacts");
    REQUIRE(run.wall_names() == std::vector<std::string>{"bottom", "top"});  // name order
    const auto top_force = run.read_wall_series("top", "force");
    const auto bottom_torque = run.read_wall_series("bottom", "torque");
    const auto bottom_displacement = run.read_wall_series("bottom", "displacement");
    const auto top_energy = run.read_wall_impact_energy("top");
    const auto bottom_impacts = run.read_wall_impacts("bottom");
    REQUIRE(top_force.size() == rows);
    REQUIRE(top_energy.size() == rows);
    REQUIRE(bottom_impacts.size() == rows);
    for (std::size_t r = 0; r < rows; ++r) {
      const SeriesRow e = make_row(static_cast<std::int64_t>(r), 2);
      CHECK(step[r] == e.step);
      CHECK(time[r] == e.time);
      CHECK(kinetic[r] == e.kinetic_energy);
      CHECK(bond[r] == e.bond_energy);
      CHECK(contact[r] == e.contact_energy);
      CHECK(intact[r] == e.bonds_intact);
      CHECK(broken[r] == e.bonds_broken);
      CHECK(contacts[r] == static_cast<double>(e.contacts));
      CHECK(top_force[r] == e.wall_force[0]);
      CHECK(bottom_torque[r] == e.wall_torque[1]);
      CHECK(bottom_displacement[r] == e.wall_displacement[1]);
      CHECK(top_energy[r] == e.wall_impact_energy[0]);
      CHECK(bottom_impacts[r] == e.wall_impacts[1]);
    }
    CHECK_THROWS_AS(run.read_wall_impacts("left"), OutputError);
    CHECK_THROWS_AS(run.read_series("kinetic"), OutputError);
    CHECK_THROWS_AS(run.read_wall_series("left", "force"), OutputError);
    CHECK_THROWS_AS(run.read_wall_series("top", "velocity"), OutputError);
  }
  SUBCASE("bond break events") {
    const auto events = run.read_break_events();
    REQUIRE(events.size() == 3 * kEventsPerFrame);
    for (std::size_t k = 0; k < events.size(); ++k) {
      const BondBreakEvent e = make_event(static_cast<std::int64_t>(k));
      const BondBreakEvent& r = events[k];
      CHECK(r.time == e.time);
      CHECK(r.step == e.step);
      CHECK(r.id_i == e.id_i);
      CHECK(r.id_j == e.id_j);
      CHECK(r.midpoint == e.midpoint);
      CHECK(r.stress.sigma_vm == e.stress.sigma_vm);
      CHECK(r.stress.sigma_axial == e.stress.sigma_axial);
      CHECK(r.stress.tau == e.stress.tau);
      CHECK(r.stress.tension == e.stress.tension);
      CHECK(r.stress.bending == e.stress.bending);
      CHECK(r.stress.shear == e.stress.shear);
      CHECK(r.stress.torsion == e.stress.torsion);
      CHECK(r.stress.dominant == e.stress.dominant);
    }
  }
}

TEST_CASE("a run with no walls, no bonds and an empty frame") {
  TempFolder folder("empty");
  const auto path = folder.path() / "run.h5";
  {
    RunWriter writer(path, RunMetadata{}, {});
    writer.append_series(make_row(0, 0));
    writer.write_frame(0, 0.0, Particles{}, Bonds{});
    writer.write_frame(1, 1e-3, make_particles(2, 1), Bonds{});
  }
  const RunFile run(path);
  REQUIRE(run.frame_count() == 2);
  CHECK(run.read_frame(0).id.empty());
  CHECK(run.read_frame(1).id.size() == 2);
  CHECK(run.read_frame(1).bond_i.empty());
  CHECK(run.wall_names().empty());
  CHECK(run.read_series("time").size() == 1);
  CHECK(run.read_break_events().empty());
}
