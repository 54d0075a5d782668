// Many bodies in one scene: [[body]] entries and body streams, their errors, body ids through the
// run and its output, and the per-body fragment statistics.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "shard/analysis/body_statistics.hpp"
#include "shard/body_impacts.hpp"
#include "shard/app/fragments_command.hpp"
#include "shard/analysis/run_tables.hpp"
#include "shard/app/run_command.hpp"
#include "shard/checkpoint.hpp"
#include "../common/installed_plugins.hpp"
#include "shard/plugin_host.hpp"
#include "shard/run_file.hpp"
#include "shard/scene.hpp"
#include "shard/simulation.hpp"
#include "shard/wall.hpp"
#include "impact_tracker.hpp"
#include "serial_backend.hpp"

using namespace shard;

namespace {

using testing::plugins;

// Two bonded bars of 10 x 2 x 2 spheres (4 mm, cubic lattice: identical packings), side by side
// 62.5 mm apart in y, tilted 20 degrees about y and dropped at 3 m/s onto a floor: the lower end
// strikes first and the bar breaks.
const std::string kHeader = R"([simulation]
duration = 0.012
dt = "auto"
seed = 5
gravity = [0, 0, -9.81]

[material]
density = 3720

[output]
frame_interval = 0.002

[contact]
plugin = "hertz_mindlin"
shear_modulus = 10e6
poisson_ratio = 0.25
friction = 0.67
restitution = 0.5

[bond]
plugin = "beam_bond"
youngs_modulus = 12.8e6
critical_stress = 0.24e6

[[wall]]
name = "floor"
shape = "plane"
point = [0, 0, 0]
normal = [0, 0, 1]
)";

std::string bar(const std::string& name, const std::string& position, const std::string& extra = "") {
  return "\n[[body]]\nname = \"" + name + "\"\nposition = " + position +
         "\nrotation_axis = [0, 1, 0]\nrotation_angle = 20\nvelocity = [0, 0, -3]\n" + extra +
         "[body.generator]\nplugin = \"box_fill\"\nmin_corner = [0, 0, 0]\nmax_corner = [0.04, 0.008, 0.008]\n"
         "diameter_min = 0.004\ndiameter_max = 0.004\nlattice = \"cubic\"\ngap = 0.3\n";
}

const std::string kTwoBars = kHeader + bar("left", "[0, 0, 0.03]") + bar("right", "[0, 0.0625, 0.03]");

std::string error_of(const std::string& text) {
  try {
    load_scene_text(text, "bodies.toml", {}, plugins());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

Scene load(const std::string& text) { return load_scene_text(text, "bodies.toml", {}, plugins()); }

}  // namespace

TEST_CASE("[[body]] entries load; the single [generator] form is one body placed as generated") {
  const Scene two = load(kTwoBars);
  REQUIRE(two.bodies.size() == 2);
  CHECK(two.bodies[0].name == "left");
  CHECK(two.bodies[1].placement.position.value() == Vec3(0, 0.0625, 0.03));
  CHECK(two.bodies[0].placement.rotation_angle == 20);

  const std::string single = kHeader +
                             "[generator]\nplugin = \"box_fill\"\nmin_corner = [0, 0, 0.01]\n"
                             "max_corner = [0.04, 0.008, 0.018]\ndiameter_min = 0.004\ndiameter_max = 0.004\n"
                             "lattice = \"cubic\"\n";
  const Scene one = load(single);
  REQUIRE(one.bodies.size() == 1);
  CHECK(one.bodies[0].from_generator_section);
  // Placed as generated: the positions are the generator's, bit for bit, all in body 0.
  const SceneInstance inst = instantiate(one, plugins(), {});
  const auto& p = inst.simulation->particles();
  REQUIRE(p.size() == 40);
  for (std::size_t k = 0; k < p.size(); ++k) {
    CHECK(p.body[k] == 0);
    CHECK(p.position[k] == inst.body.position[k]);
    CHECK(p.velocity[k] == Vec3::Zero());
  }
}

TEST_CASE("--set reaches a body's placement, generator and stream by name") {
  const Scene s = load_scene_text(kTwoBars, "bodies.toml",
                                  {"body.right.velocity=[0, 0, -5]", "body.left.generator.diameter_max=0.005",
                                   "body.left.generator.diameter_min=0.005"},
                                  plugins());
  CHECK(s.bodies[1].placement.velocity == Vec3(0, 0, -5));
  CHECK(s.bodies[0].placement.velocity == Vec3(0, 0, -3));
  CHECK(s.bodies[0].generator.params.number("diameter_max") == 0.005);
  CHECK(s.bodies[1].generator.params.number("diameter_max") == 0.004);
  auto error = [](const std::vector<std::string>& set) {
    try {
      load_scene_text(kTwoBars, "bodies.toml", set, plugins());
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(error({"body.middle.velocity=[0, 0, -1]"}).find("no [[body]] named 'middle'") != std::string::npos);
  CHECK(error({"body.left.gen.diameter_max=1"}).find("a body's tables are 'generator' and 'stream'") !=
        std::string::npos);
  // A stream's copies and seed: what a sweep over packings varies.
  const std::string generator = bar("x", "[0,0,0]").substr(bar("x", "[0,0,0]").find("[body.generator]"));
  const std::string stream = kHeader + "\n[[body]]\nname = \"bars\"\n" + generator +
                             "[body.stream]\ncopies = 2\nstart = [0, 0, 0.04]\nspacing = [0.06, 0, 0]\n";
  const Scene more = load_scene_text(stream, "bodies.toml", {"body.bars.stream.copies=4", "body.bars.stream.seed=9"},
                                     plugins());
  CHECK(more.bodies[0].stream->copies == 4);
  CHECK(more.bodies[0].stream->seed == 9);
}

TEST_CASE("bad body input is refused with file:line:column, the key and the fix") {
  // Both forms at once.
  const std::string both = kTwoBars + "\n[generator]\nplugin = \"box_fill\"\n";
  CHECK(error_of(both).find("bodies.toml:") == 0);
  CHECK(error_of(both).find("both a [generator] section and [[body]] entries") != std::string::npos);
  // An unknown placement key, with the closest valid one.
  const std::string typo = kHeader + bar("left", "[0, 0, 0.03]", "velocty = [0, 0, -1]\n");
  CHECK(error_of(typo).find("unknown key 'velocty' in [body] (did you mean 'velocity'?)") != std::string::npos);
  CHECK(error_of(typo).find("bodies.toml:") == 0);
  // An unknown generator parameter is the plugin's error, naming [body.generator]'s key.
  const std::string generator_typo = kHeader + bar("left", "[0, 0, 0.03]") + "lattise = \"fcc\"\n";
  CHECK(error_of(generator_typo).find("lattise") != std::string::npos);
  // [body] instead of [[body]].
  CHECK(error_of(kHeader + "[body]\nname = \"a\"\n").find("write [[body]], not [body]") != std::string::npos);
  // Two bodies with one name.
  CHECK(error_of(kHeader + bar("a", "[0, 0, 0.03]") + bar("a", "[0, 0.1, 0.03]")).find("used by two bodies") !=
        std::string::npos);
  // A stream without spacing, and a stream with a position.
  const std::string stream = "[body.stream]\ncopies = 3\nstart = [0, 0, 0.03]\n";
  CHECK(error_of(kHeader + bar("s", "[0, 0, 0.03]") + stream).find("remove one") != std::string::npos);
  const std::string no_position = std::string(kHeader) + "\n[[body]]\nname = \"s\"\n" +
                                  bar("x", "[0,0,0]").substr(bar("x", "[0,0,0]").find("[body.generator]"));
  CHECK(error_of(no_position + stream).find("[body.stream] spacing is missing or zero") != std::string::npos);
  CHECK(error_of(no_position + stream + "spacing = [0.1, 0, 0]\nbogus = 1\n").find("unknown key 'bogus' in "
                                                                                    "[body.stream]") !=
        std::string::npos);
}

TEST_CASE("overlapping bodies and a stream that cannot fit are refused at placement") {
  // The right bar 5 mm beside the left one: their 8 mm wide packings overlap.
  const Scene overlap = load(kHeader + bar("left", "[0, 0, 0.03]") + bar("right", "[0, 0.005, 0.03]"));
  try {
    instantiate(overlap, plugins(), {});
    FAIL("overlapping bodies were accepted");
  } catch (const SceneError& e) {
    const std::string what = e.what();
    CHECK(what.find("bodies.toml:") == 0);
    CHECK(what.find("'left'") != std::string::npos);
    CHECK(what.find("'right' overlap at placement") != std::string::npos);
  }
  // Touching is not overlapping: 8 mm apart the outer spheres touch exactly.
  CHECK_NOTHROW(instantiate(load(kHeader + bar("left", "[0, 0, 0.03]") + bar("right", "[0, 0.008, 0.03]")),
                            plugins(), {}));
  const std::string generator = bar("x", "[0,0,0]").substr(bar("x", "[0,0,0]").find("[body.generator]"));
  const std::string tight = kHeader + "\n[[body]]\nname = \"bars\"\nvelocity = [0, 0, -3]\n" + generator +
                            "[body.stream]\ncopies = 4\nstart = [0, 0, 0.03]\nspacing = [0, 0.006, 0]\n";
  try {
    instantiate(load(tight), plugins(), {});
    FAIL("a stream of overlapping copies was accepted");
  } catch (const SceneError& e) {
    const std::string what = e.what();
    CHECK(what.find("'bars#0'") != std::string::npos);
    CHECK(what.find("'bars#1' overlap at placement") != std::string::npos);
    CHECK(what.find("the stream cannot fit its copies") != std::string::npos);
  }
}

TEST_CASE("a body stream copies one packing rigidly: same shape, random orientation, scattered speed") {
  const std::string generator = bar("x", "[0,0,0]").substr(bar("x", "[0,0,0]").find("[body.generator]"));
  const std::string text = kHeader + "\n[[body]]\nname = \"bars\"\nvelocity = [0, 0, -3]\n" + generator +
                           "[body.stream]\ncopies = 5\nstart = [0, 0, 0.04]\nspacing = [0.06, 0, 0]\n"
                           "jitter = [0.001, 0.001, 0.001]\nrandom_orientation = true\nspeed_scatter = 0.2\n"
                           "seed = 11\n";
  const SceneInstance inst = instantiate(load(text), plugins(), {});
  const Particles& p = inst.simulation->particles();
  REQUIRE(p.size() == 5 * 40);
  REQUIRE(inst.body_names.size() == 5);
  CHECK(inst.body_names[3] == "bars#3");
  std::set<double> speeds;
  for (std::size_t c = 0; c < 5; ++c) {
    Vec3 centre = Vec3::Zero();
    for (std::size_t k = 0; k < 40; ++k) {
      const std::size_t row = c * 40 + k;
      CHECK(p.body[row] == static_cast<std::int32_t>(c));
      centre += p.position[row] / 40.0;
      // A rigid copy: every distance inside the body equals copy 0's (rounding: a few 1e-18 m).
      for (std::size_t j = 0; j < k; ++j)
        CHECK((p.position[row] - p.position[c * 40 + j]).norm() ==
              doctest::Approx((p.position[k] - p.position[j]).norm()).epsilon(1e-12));
      // Translation only: every sphere of a copy moves at the copy's velocity.
      CHECK(p.velocity[row] == p.velocity[c * 40]);
    }
    // Centre of mass (equal spheres) at start + c spacing within the jitter.
    CHECK((centre - Vec3(0.06 * static_cast<double>(c), 0, 0.04)).cwiseAbs().maxCoeff() <= 0.001 + 1e-12);
    const double speed = p.velocity[c * 40].norm();
    CHECK(speed >= 3 * 0.8);
    CHECK(speed <= 3 * 1.2);
    speeds.insert(speed);
  }
  CHECK(speeds.size() == 5);  // scattered: no two copies alike
  // Bonds only inside a body.
  for (std::size_t b = 0; b < inst.simulation->bonds().size(); ++b)
    CHECK(p.body[static_cast<std::size_t>(inst.simulation->bonds().i[b])] ==
          p.body[static_cast<std::size_t>(inst.simulation->bonds().j[b])]);
}

TEST_CASE("two identical bars dropped identically keep their body ids, never bond across, and break alike") {
  const auto dir = std::filesystem::temp_directory_path() / "shard_test_bodies";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto scene_file = dir / "two_bars.toml";
  std::ofstream(scene_file) << kTwoBars;
  RunOptions options;
  options.scene = scene_file;
  options.out_dir = dir / "out";
  options.quiet = true;
  std::ostringstream log;
  const RunSummary summary = run_scene(options, log);
  REQUIRE(summary.particles == 80);
  CHECK(summary.bonds_broken > 0);

  {
    const RunFile run(summary.output);
    REQUIRE(run.frame_count() > 2);
    // First wall contact: the bars fall without turning until the lowest sphere reaches the floor,
    // so the centre of mass then moves at sqrt(v0^2 + 2 g h), h = the lowest sphere's initial
    // height above touching, straight down onto the floor's normal (angle 0).
    const FrameData start = run.read_frame(0);
    double h = 1e9;
    for (std::size_t k = 0; k < start.id.size(); ++k) h = std::min(h, start.position[k].z() - start.radius[k]);
    const double expected_speed = std::sqrt(3.0 * 3.0 + 2 * 9.81 * h);
    const double expected_time = (std::sqrt(3.0 * 3.0 + 2 * 9.81 * h) - 3.0) / 9.81;
    const std::vector<BodyImpact> impacts = run.read_body_impacts();
    REQUIRE(impacts.size() == 2);
    for (const BodyImpact& i : impacts) {
      CHECK(i.hit);
      CHECK(i.wall == 0);
      CHECK(i.normal == Vec3::UnitZ());
      // Recorded at the end of the first step in contact: up to one step (~1e-5 s) late, after one
      // step of contact force on the touching spheres; measured 0.064 % below free fall, 3.9e-6 s late.
      CHECK(i.speed() == doctest::Approx(expected_speed).epsilon(1e-3));
      CHECK(i.time == doctest::Approx(expected_time).epsilon(0.01).scale(0));
      CHECK(i.angle_degrees() < 0.5);
    }
    CHECK(impacts[0].step == impacts[1].step);
    CHECK(impacts[0].speed() == doctest::Approx(impacts[1].speed()).epsilon(1e-9));
    for (std::size_t f = 0; f < run.frame_count(); ++f) {
      const FrameData frame = run.read_frame(f);
      // Ids 0..39 were generated in body 0, 40..79 in body 1, whatever the row order.
      for (std::size_t k = 0; k < frame.id.size(); ++k) CHECK(frame.body[k] == (frame.id[k] < 40 ? 0 : 1));
      for (std::size_t b = 0; b < frame.bond_i.size(); ++b)
        CHECK(frame.body[static_cast<std::size_t>(frame.bond_i[b])] ==
              frame.body[static_cast<std::size_t>(frame.bond_j[b])]);
    }
  }

  analysis::BodyReport report;
  std::multiset<std::size_t> sizes_left, sizes_right;
  {
    const RunFile file(summary.output);  // closed before the command reopens it for writing
    const FrameData last = file.read_frame(file.frames().back());
    const auto fragments = analysis::analyse_fragments(analysis::particle_sample(last), analysis::bond_list(last));
    report = analysis::body_statistics(analysis::particle_sample(last), fragments.fragments, 0.9, 0.005);
    for (const auto& f : fragments.fragments) (f.body == 0 ? sizes_left : sizes_right).insert(f.particles);
  }
  REQUIRE(report.bodies.size() == 2);
  const auto& left = report.bodies[0];
  const auto& right = report.bodies[1];
  CHECK(left.particles == 40);
  CHECK(right.particles == 40);
  CHECK(left.fragments > 1);
  // Rigid-body invariance: the right bar is the left one moved 62.5 mm along y; the two differ only
  // by the rounding of that shift, so they break into the same pieces.
  CHECK(left.fragments == right.fragments);
  CHECK(left.broken == right.broken);
  CHECK(sizes_left == sizes_right);
  CHECK(left.fsd.x50 == doctest::Approx(right.fsd.x50).epsilon(1e-9));
  CHECK(report.breakage_probability == (left.broken ? 1.0 : 0.0));

  // The command: the table in the run file and the CSV.
  FragmentsOptions fo;
  fo.run_file = summary.output;
  fo.by_body = true;
  fo.body_csv = dir / "bodies.csv";
  fo.fines_size = 0.005;
  std::ostringstream out, err;
  const int status = fragments_command(fo, out, err);
  CAPTURE(err.str());
  REQUIRE(status == 0);
  CHECK(out.str().find("bodies 2  broken") != std::string::npos);
  std::ifstream csv(*fo.body_csv);
  std::string header, row0, row1, extra;
  std::getline(csv, header);
  std::getline(csv, row0);
  std::getline(csv, row1);
  CHECK(header.rfind("body,particles,mass_kg,fragments,", 0) == 0);
  CHECK(header.find(",impacted,impact_time_s,impact_speed_m_s,impact_angle_deg,impact_wall") != std::string::npos);
  CHECK(row0.rfind("0,40,", 0) == 0);
  CHECK(row1.rfind("1,40,", 0) == 0);
  CHECK_FALSE(std::getline(csv, extra));
}

TEST_CASE("body ids survive a checkpoint and restart: the continued run ends as the uninterrupted one") {
  const auto dir = std::filesystem::temp_directory_path() / "shard_test_bodies_restart";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto scene_file = dir / "two_bars.toml";
  std::ofstream(scene_file) << kTwoBars;
  std::ostringstream log;
  RunOptions reference;
  reference.scene = scene_file;
  reference.out_dir = dir / "reference";
  reference.quiet = true;
  const RunSummary whole = run_scene(reference, log);
  REQUIRE(whole.bonds_broken > 0);

  RunOptions first = reference;
  first.out_dir = dir / "interrupted";
  first.interrupt_at_step = whole.steps / 2;
  REQUIRE(run_scene(first, log).interrupted());
  // The checkpoint holds the body of every particle.
  const Checkpoint c = read_checkpoint(dir / "interrupted" / "run.checkpoint.h5");
  REQUIRE(c.simulation.particles.body.size() == 80);
  for (std::size_t k = 0; k < 80; ++k)
    CHECK(c.simulation.particles.body[k] == (c.simulation.particles.id[k] < 40 ? 0 : 1));

  RunOptions second = reference;
  second.scene.clear();
  second.out_dir = dir / "interrupted";
  second.restart = dir / "interrupted" / "run.h5";
  const RunSummary resumed = run_scene(second, log);
  CHECK(resumed.bonds_broken == whole.bonds_broken);
  const RunFile a(dir / "reference" / "run.h5"), b(dir / "interrupted" / "run.h5");
  REQUIRE(a.frame_count() == b.frame_count());
  for (std::size_t k = 0; k < a.frame_count(); ++k) {
    const FrameData fa = a.read_frame(k), fb = b.read_frame(k);
    CHECK(fa.body == fb.body);  // frames copied from the interrupted file and written after the restart
    CHECK(fa.position == fb.position);
  }
  // The first contacts are carried by the checkpoint: the same record as without the stop.
  const auto ia = a.read_body_impacts(), ib = b.read_body_impacts();
  REQUIRE(ia.size() == 2);
  REQUIRE(ib.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(ia[k].hit);
    CHECK(ia[k].step == ib[k].step);
    CHECK(ia[k].velocity == ib[k].velocity);
  }
}

TEST_CASE("a stream over a region places copies at random, apart by a bounding diameter, or says it cannot fit") {
  const std::string generator = bar("x", "[0,0,0]").substr(bar("x", "[0,0,0]").find("[body.generator]"));
  const std::string head = kHeader + "\n[[body]]\nname = \"bars\"\nvelocity = [0, 0, -3]\n" + generator;
  const std::string roomy = head + "[body.stream]\ncopies = 4\nregion_min = [0, 0, 0.05]\nregion_max = [0.3, 0.3, 0.1]\n"
                                   "random_orientation = true\nseed = 3\n";
  const SceneInstance inst = instantiate(load(roomy), plugins(), {});
  const Particles& p = inst.simulation->particles();
  REQUIRE(p.size() == 4 * 40);
  // The bar's bounding radius about its centre: half its 40 x 8 x 8 mm diagonal of sphere centres
  // (36 x 4 x 4 mm) plus one radius.
  const double bound = 0.5 * std::sqrt(0.036 * 0.036 + 2 * 0.004 * 0.004) + 0.002;
  std::vector<Vec3> centres(4, Vec3::Zero());
  for (std::size_t k = 0; k < p.size(); ++k) centres[static_cast<std::size_t>(p.body[k])] += p.position[k] / 40.0;
  for (std::size_t a = 0; a < 4; ++a) {
    CHECK(centres[a].x() >= -1e-12);
    CHECK(centres[a].x() <= 0.3 + 1e-12);
    CHECK(centres[a].z() >= 0.05 - 1e-12);
    for (std::size_t b = 0; b < a; ++b) CHECK((centres[a] - centres[b]).norm() >= 2 * bound - 1e-12);
  }
  const std::string cramped = head + "[body.stream]\ncopies = 10\nregion_min = [0, 0, 0.05]\n"
                                     "region_max = [0.05, 0.05, 0.06]\n";
  try {
    instantiate(load(cramped), plugins(), {});
    FAIL("ten bars were fitted into a 5 x 5 x 1 cm box");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()).find("the region cannot fit 10 copies") != std::string::npos);
    CHECK(std::string(e.what()).find("bodies.toml:") == 0);
  }
  CHECK(error_of(head + "[body.stream]\ncopies = 2\nregion_min = [0, 0, 0]\nregion_max = [1, 1, 1]\n"
                        "spacing = [0.1, 0, 0]\n")
            .find("[body.stream] spacing is given with a region") != std::string::npos);
  CHECK(error_of(head + "[body.stream]\ncopies = 2\nregion_min = [0, 0, 0]\nregion_max = [1, -1, 1]\n")
            .find("must not lie below it") != std::string::npos);
}

namespace {

// Every (particle id, wall) pair touching now, by testing every sphere against every wall with the
// kernel's contact condition (closer than the radius).
std::map<std::pair<Index, std::int32_t>, Vec3> touching_now(const Simulation& sim) {
  std::map<std::pair<Index, std::int32_t>, Vec3> out;
  const Particles& p = sim.particles();
  for (std::size_t k = 0; k < p.size(); ++k)
    for (std::size_t w = 0; w < sim.walls().size(); ++w) {
      Vec3 normal;
      double distance = 0;
      if (wall_contact(sim.walls()[w], p.position[k], p.radius[k], normal, distance) && distance < p.radius[k])
        out[{p.id[k], static_cast<std::int32_t>(w)}] = normal;
    }
  return out;
}

}  // namespace

TEST_CASE("the impacts come from the kernel's begun wall contacts and equal a scan of every sphere at every step") {
  for (const bool belt : {false, true}) {
    CAPTURE(belt);
    std::string text = kTwoBars;
    // The same floor as a belt: it carries, so the bars record no impact although they land on it.
    if (belt) text.replace(text.find("normal = [0, 0, 1]\n"), 19, "normal = [0, 0, 1]\nbelt_speed = 0.5\nbelt_direction = [1, 0, 0]\n");
    const Scene scene = load(text);
    // The run driver's tracker over a serial run, as `shard run` records /body_impacts.
    driver::detail::SerialBackend run;
    driver::detail::ScenePart part = run.instantiate(scene, plugins(), {});
    run.start(scene, part, nullptr);
    const Simulation& sim = run.local();
    driver::detail::ImpactTracker recorder(part.whole.bodies);
    std::map<std::pair<Index, std::int32_t>, Vec3> before = touching_now(sim);
    std::vector<std::int64_t> first_step(2, -1);
    std::vector<Vec3> first_velocity(2, Vec3::Zero()), first_normal(2, Vec3::Zero());
    std::size_t begun_total = 0;
    while (sim.time() < 0.012) {
      run.step();
      recorder.update(run);
      const auto now = touching_now(sim);
      std::map<std::pair<Index, std::int32_t>, Vec3> begun;
      for (const WallContactStart& c : sim.wall_contacts_begun())
        begun[{sim.particles().id[static_cast<std::size_t>(c.particle)], c.wall}] = c.normal;
      REQUIRE(begun.size() == sim.wall_contacts_begun().size());  // each pair once
      begun_total += begun.size();
      for (const auto& [pair, normal] : now)
        if (!before.count(pair)) {
          REQUIRE(begun.count(pair) == 1);
          CHECK(begun[pair] == normal);
        }
      for (const auto& [pair, normal] : begun) CHECK((now.count(pair) == 1 && before.count(pair) == 0));
      // The scan's first impact per body: lowest wall, then lowest sphere index; the centre-of-mass
      // velocity summed in particle order.
      const Particles& p = sim.particles();
      for (std::size_t b = 0; b < 2; ++b) {
        if (first_step[b] >= 0 || belt) continue;
        for (std::size_t k = 0; k < p.size() && first_step[b] < 0; ++k) {
          const auto at = now.find({p.id[k], 0});
          if (p.body[k] != static_cast<std::int32_t>(b) || at == now.end()) continue;
          first_step[b] = sim.step_count();
          first_normal[b] = at->second;
          Vec3 momentum = Vec3::Zero();
          double mass = 0;
          for (std::size_t q = 0; q < p.size(); ++q)
            if (p.body[q] == static_cast<std::int32_t>(b)) {
              momentum += p.mass[q] * p.velocity[q];
              mass += p.mass[q];
            }
          first_velocity[b] = momentum / mass;
        }
      }
      before = now;
    }
    CHECK(begun_total > 0);
    for (std::size_t b = 0; b < 2; ++b) {
      const BodyImpact& i = recorder.impacts()[b];
      if (belt) {
        CHECK_FALSE(i.hit);
        continue;
      }
      REQUIRE(first_step[b] > 0);
      CHECK(i.hit);
      CHECK(i.step == first_step[b]);
      CHECK(i.velocity == first_velocity[b]);
      CHECK(i.normal == first_normal[b]);
      CHECK(i.wall == 0);
    }
  }
}
