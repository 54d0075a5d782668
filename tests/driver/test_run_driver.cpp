// One run through the driver: the hooks in their documented order, stop rules, the result against
// the run file it wrote, and typed overrides against the --set text they replace.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "driver_fixtures.hpp"
#include "shard/driver/fragment_labeller.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/stop_rules.hpp"
#include "shard/run_file.hpp"
#include "shard/scene.hpp"

using namespace shard;
using namespace shard::driver;
using shard::test::kTinyBeam;
using shard::test::plugins;
using shard::test::scratch;

namespace {

// Writes down every hook with its step, under a name, into a shared journal.
class Journal : public RunObserver {
 public:
  Journal(std::string name, std::vector<std::string>& journal) : name_(std::move(name)), journal_(journal) {}
  void on_start(RunState& r) override { note("start", r); }
  void on_series(RunState& r, const Energies&) override { note("series", r); }
  void before_frame(RunState& r) override { note("before_frame", r); }
  void on_frame(RunState& r) override { note("frame", r); }
  void on_step(RunState& r) override { note("step", r); }
  void on_stop(RunState& r) override { note("stop", r); }
  void on_closed(RunState& r) override { note("closed", r); }
  void on_finish(RunState& r) override { note("finish", r); }

 private:
  void note(const char* hook, const RunState& r) {
    journal_.push_back(name_ + ":" + hook + "@" + std::to_string(r.sim.step_count()));
  }
  std::string name_;
  std::vector<std::string>& journal_;
};

// Ends the run after `rows` series rows of the loop.
class StopAfterRows : public RunObserver {
 public:
  explicit StopAfterRows(int rows) : rows_(rows) {}
  void on_series(RunState& r, const Energies&) override {
    if (++seen_ == rows_) r.request_stop(StopReason::Observer, "enough rows for the test");
  }

 private:
  int rows_, seen_ = 0;
};

RunSpec tiny_spec(const std::string& name) {
  RunSpec spec;
  spec.scene = kTinyBeam;
  spec.out_dir = scratch(name);
  spec.threads = 1;
  return spec;
}

std::size_t count(const std::vector<std::string>& journal, const std::string& prefix) {
  return static_cast<std::size_t>(
      std::count_if(journal.begin(), journal.end(), [&](const std::string& e) { return e.rfind(prefix, 0) == 0; }));
}

}  // namespace

TEST_CASE("the hooks are called in the documented order, each round in the order the observers were composed") {
  std::vector<std::string> journal;
  Journal a("a", journal), b("b", journal);
  StopAfterRows stop(5);
  RunSpec spec = tiny_spec("hook_order");
  // Frames every 2 rows' time, so the loop writes frames too (rows every 1e-4 s).
  spec.overrides = {{"output.frame_interval", 2e-4}};
  const RunResult r = run(spec, plugins(), {&a, &stop, &b});
  REQUIRE(r.stop == StopReason::Observer);
  REQUIRE(!journal.empty());
  // A fresh run writes its first frame (step 0), then starts the loop.
  CHECK(journal[0] == "a:before_frame@0");
  CHECK(journal[1] == "b:before_frame@0");
  CHECK(journal[2] == "a:start@0");
  CHECK(journal[3] == "b:start@0");
  // The stop request in `stop`'s on_series ends the round: `b` does not see that row, and no
  // frame or step hook follows it.
  const std::string last_row = "a:series@" + std::to_string(r.steps);
  const auto at = std::find(journal.begin(), journal.end(), last_row);
  REQUIRE(at != journal.end());
  CHECK(*(at + 1) == "a:stop@" + std::to_string(r.steps));
  CHECK(count(journal, "a:series") == 5);
  CHECK(count(journal, "b:series") == 4);
  // Every frame of the loop: before_frame, then on_frame, a before b.
  CHECK(count(journal, "a:frame") == count(journal, "b:frame"));
  CHECK(count(journal, "a:frame") >= 1);
  // The end: stop, (closing frame's before_frame), closed, finish; the last entry is b's finish.
  CHECK(journal.back() == "b:finish@" + std::to_string(r.steps));
  CHECK(journal[journal.size() - 2] == "a:finish@" + std::to_string(r.steps));
  CHECK(journal[journal.size() - 3] == "b:closed@" + std::to_string(r.steps));
  // The curve: the first row and the five of the loop (the stop fell on a row's step: no closing row).
  CHECK(r.curve.size() == 6);
}

TEST_CASE("the scene's stop rule ends the run at the first row past max_displacement") {
  MaxDisplacementStop rule;
  RunSpec spec = tiny_spec("max_displacement");
  const double limit = 2e-4;  // m of pin travel: 10 ms at 0.02 m/s
  spec.overrides = {{"stop.max_displacement", limit}};
  const RunResult r = run(spec, plugins(), {&rule});
  CHECK(r.stop == StopReason::MaxDisplacement);
  CHECK(r.stop_reason == "the loading walls reached max_displacement");
  // A row every 1e-4 s rounded to whole steps; the pins move at 0.02 m/s from the start (no ramp),
  // so the run stops within one row's travel past the limit.
  const double row_travel = 0.02 * static_cast<double>(std::llround(1e-4 / r.dt)) * r.dt;
  CHECK(r.final_displacement >= limit);
  CHECK(r.final_displacement < limit + row_travel * (1 + 1e-9));
  const std::size_t rows = r.curve.size();
  REQUIRE(rows >= 2);
  CHECK(r.curve.displacement[rows - 2] < limit);
}

TEST_CASE("the result is what the run file holds: the curve, the breaks, the fragments of the last frame") {
  FragmentLabeller labeller;
  MaxDisplacementStop stop;
  LoadDropStop drop;
  RunSpec spec = tiny_spec("result_vs_file");
  // To the scene's own stop (half the peak load after breakage, or 3 mm), labels in every frame.
  spec.overrides = {{"analysis.fragments_every", std::int64_t{1}}};
  const RunResult r = run(spec, plugins(), {&drop, &stop, &labeller});
  REQUIRE(r.bonds_broken > 0);
  const RunFile file(r.output);
  const std::size_t rows = file.series_rows();
  REQUIRE(rows == r.curve.size());
  const auto time = file.read_series("time");
  const auto broken = file.read_integer_series("bonds_broken");
  const auto step = file.read_integer_series("step");
  CHECK(step.back() == r.steps);
  CHECK(broken.back() == r.bonds_broken);
  // The load sensor is the pins' force along -z, the displacement their mean travel along -z:
  // recomputed from the file's wall series the same way, bit for bit.
  const auto fl = file.read_wall_series("pin_left", "force"), fr = file.read_wall_series("pin_right", "force");
  const auto dl = file.read_wall_series("pin_left", "displacement"),
             dr = file.read_wall_series("pin_right", "displacement");
  const Vec3 down(0, 0, -1);
  for (std::size_t k = 0; k < rows; ++k) {
    CHECK(r.curve.time[k] == time[k]);
    CHECK(r.curve.force[k] == (0.0 - fl[k].dot(down)) - fr[k].dot(down));
    CHECK(r.curve.displacement[k] == (dl[k].dot(down) + dr[k].dot(down)) / 2.0);
  }
  CHECK(r.peak_load == *std::max_element(r.curve.force.begin(), r.curve.force.end()));
  // The fragments of the last frame, from its stored labels.
  const FrameData last = file.read_frame(file.frame_count() - 1);
  REQUIRE(last.fragment.has_value());
  const Index labels = *std::max_element(last.fragment->begin(), last.fragment->end()) + 1;
  std::vector<std::size_t> sizes(static_cast<std::size_t>(labels), 0);
  for (Index l : *last.fragment) ++sizes[static_cast<std::size_t>(l)];
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  CHECK(r.fragment_particles == sizes);
  CHECK(std::accumulate(sizes.begin(), sizes.end(), std::size_t{0}) == r.particles);
}

TEST_CASE("a settled run starts its clock, its pins and its curve at rest under the body's weight") {
  MaxDisplacementStop rule;
  RunSpec spec = tiny_spec("settled");
  spec.overrides = {{"simulation.gravity", Vec3(0, 0, -9.81)},
                    {"simulation.settle_time", 0.02},
                    {"stop.max_displacement", 2e-4}};
  std::vector<std::string> lines;
  const RunResult r = run(spec, plugins(), {&rule}, RunLog{[&](const std::string& l) { lines.push_back(l); }, {}});
  const auto settled = std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return l.rfind("settled", 0) == 0; });
  REQUIRE(settled != lines.end());
  MESSAGE(*settled);
  // The automatic step settles in steps shorter by 1 / sqrt(1 + settle_damping 0.5); the loading
  // takes the automatic step itself.
  const std::string step_text = " steps of ";
  const auto at = settled->find(step_text);
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(settled->substr(at + step_text.size())) == doctest::Approx(r.dt / std::sqrt(1.5)).epsilon(1e-3));
  // The beam sank onto its rollers; the pins were brought down onto it before the test began.
  for (const char* pin : {"seated pin_left ", "seated pin_right "})
    CHECK(std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(pin, 0) == 0; }));
  // The curve starts where the loading does: t = 0, the pins not yet moved. The pins were held
  // while the beam settled, so their first row is where the scene put them.
  REQUIRE(r.curve.size() >= 2);
  CHECK(r.curve.time.front() == 0.0);
  CHECK(r.curve.displacement.front() == 0.0);
  // The loading then runs as without settling: 0.02 m/s from t = 0 (no ramp), whole steps.
  for (std::size_t k = 0; k < r.curve.size(); ++k)
    CHECK(r.curve.displacement[k] == doctest::Approx(0.02 * r.curve.time[k]).epsilon(1e-9).scale(1e-12));
  CHECK(r.stop == StopReason::MaxDisplacement);
}

TEST_CASE("a typed override resolves the scene exactly as the --set text of the same value") {
  const Scene typed = load_scene(kTinyBeam, plugins(),
                                 {{"bond.youngs_modulus", 13.5e6},
                                  {"simulation.seed", std::int64_t{7}},
                                  {"wall.pin_left.velocity", Vec3(0, 0, -0.01)},
                                  {"simulation.breakage", false}});
  const Scene text = load_scene(kTinyBeam,
                                {"bond.youngs_modulus=13.5e6", "simulation.seed=7",
                                 "wall.pin_left.velocity=[0.0, 0.0, -0.01]", "simulation.breakage=false"},
                                plugins());
  CHECK(typed.resolved_text == text.resolved_text);
  CHECK(typed.bond->params.number("youngs_modulus") == 13.5e6);
  CHECK(typed.seed == 7);
  CHECK_FALSE(typed.breakage);
  // A value no scene key takes from the command line is refused by name.
  CHECK_THROWS_WITH_AS(SceneOverride::parse("bond.x={a = 1}"), doctest::Contains("a table value"), SceneError);
}

TEST_CASE("breakage has one switch: [bond] breakage is refused with the hint to [simulation] breakage") {
  CHECK_THROWS_WITH_AS(load_scene(kTinyBeam, plugins(), {{"bond.breakage", false}}),
                       doctest::Contains("[simulation] breakage = false"), SceneError);
}
