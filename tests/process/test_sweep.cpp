// `shard sweep` end to end on a small plates_drop (3 shards per run): the plates of every run are
// the ones `shard fragments --by-body` finds in the same run file, seeds change the packing,
// faster impacts do not break fewer plates beyond the bands, a failing run leaves the others
// running, and bad --vary input is refused before any run with the key and the fix.
#include <doctest/doctest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "shard/app/fragments_command.hpp"
#include "shard/run_file.hpp"
#include "shard/app/sweep_command.hpp"
#include "shard/scene.hpp"

using namespace shard;

namespace {

namespace fs = std::filesystem;

const fs::path kScene = fs::path(SHARD_SOURCE_DIR) / "scenes" / "plates_drop.toml";

// plates_drop with 3 shards instead of 6, a narrower speed scatter and a shorter run: the slowest
// shard (0.8 x 0.8 m/s from ~26 mm) lands by ~31 ms.
SweepOptions small_sweep(const std::string& vary, const fs::path& out, int seeds) {
  SweepOptions o;
  o.scene = kScene;
  o.vary = vary;
  o.sets = {"body.shard.stream.copies=3", "body.shard.stream.speed_scatter=0.2", "simulation.duration=0.045"};
  o.seeds = seeds;
  o.workers = 2;
  o.out = out;
  o.quiet = true;
  return o;
}

std::string refusal(const std::string& vary) {
  std::ostringstream log;
  SweepOptions o = small_sweep(vary, fs::temp_directory_path() / "refused", 1);
  try {
    run_sweep(o, log);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(accepted)";
}

std::vector<std::map<std::string, std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream h(line);
  for (std::string c; std::getline(h, c, ',');) names.push_back(c);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::map<std::string, std::string> row;
    std::size_t k = 0;
    for (std::string c; std::getline(s, c, ',') && k < names.size(); ++k) row[names[k]] = c;
    rows.push_back(row);
  }
  return rows;
}

std::vector<double> first_frame_radii(const fs::path& run) {
  const RunFile f(run);
  return f.read_frame(f.frames().front()).radius;
}

}  // namespace

TEST_CASE("bad --vary input is refused before any run, naming the key and the fix") {
  const std::string unknown = refusal("body.shard.stream.speed=1,2");
  CHECK(unknown.find("--vary 'body.shard.stream.speed=1,2'") != std::string::npos);
  CHECK(unknown.find("speed") != std::string::npos);
  CHECK(unknown.find("did you mean") != std::string::npos);
  const std::string no_body = refusal("body.plates.velocity=1,2");
  CHECK(no_body.find("no [[body]] named 'plates'") != std::string::npos);
  CHECK(no_body.find("the scene's [[body]] names: shard") != std::string::npos);
  CHECK(unknown.find(":0:0:") == std::string::npos);
  const std::string empty = refusal("body.shard.velocity=");
  CHECK(empty.find("no values") != std::string::npos);
  const std::string blank = refusal("body.shard.velocity=1,,2");
  CHECK(blank.find("empty value") != std::string::npos);
  const std::string word = refusal("body.shard.velocity=1.0,fast");
  CHECK(word.find("'fast' is not a number") != std::string::npos);
  CHECK(refusal("body.shard.velocity=1,1").find("given twice") != std::string::npos);
  CHECK(refusal("body.shard.velocity=-1,1").find("cannot be negative") != std::string::npos);
  CHECK(refusal("body.shard.velocity[3]=1").find("KEY[0], KEY[1] or KEY[2]") != std::string::npos);
  CHECK(refusal("body.shard.stream.copies=2,2.5").find("whole numbers") != std::string::npos);
  CHECK(refusal("body.shard.velocity").find("expected KEY=V1,V2") != std::string::npos);
  CHECK(refusal("simulation.duration[2]=1").find("no 3-vector") != std::string::npos);
}

TEST_CASE("a sweep over impact speed and seeds: per-run plates equal --by-body, seeds repack, faster breaks more") {
  const fs::path out = fs::temp_directory_path() / "speed_sweep";
  fs::remove_all(out);
  std::ostringstream log;
  const SweepResult r = run_sweep(small_sweep("body.shard.velocity=0.8,2.5", out, 2), log);
  REQUIRE(r.runs.size() == 4);
  for (const SweepRun& run : r.runs) CHECK_MESSAGE(!run.failed(), run.error);
  REQUIRE(r.plates.size() == 12);
  CHECK(r.value_label.find("|body.shard.velocity| along [0, 0, -1]") != std::string::npos);

  // Seeds change the packing (the [simulation] seed drives stl_fill): other sphere sizes.
  CHECK(first_frame_radii(out / "runs" / "v0.8_s0" / "run.h5") != first_frame_radii(out / "runs" / "v0.8_s1" / "run.h5"));

  // The per-run numbers are those of `shard fragments --by-body` on the same run file.
  for (const std::string label : {"v2.5_s1", "v0.8_s0"}) {
    const fs::path body_csv = out / (label + "_bodies.csv");
    FragmentsOptions fo;
    fo.run_file = out / "runs" / label / "run.h5";
    fo.by_body = true;
    fo.body_csv = body_csv;
    std::ostringstream fout, ferr;
    REQUIRE(fragments_command(fo, fout, ferr) == 0);
    const auto rows = read_csv(body_csv);
    std::vector<const analysis::PlateOutcome*> mine;
    for (const auto& p : r.plates)
      if (p.run == label) mine.push_back(&p);
    REQUIRE(rows.size() == mine.size());
    REQUIRE(rows.size() == 3);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      CHECK(std::stoi(rows[k].at("body")) == mine[k]->body);
      CHECK(std::stoi(rows[k].at("broken")) == (mine[k]->broken ? 1 : 0));
      CHECK(std::stoul(rows[k].at("fragments")) == mine[k]->fragments);
      CHECK(std::stod(rows[k].at("x50_m")) == mine[k]->x50);  // 17 digits: the same double
      CHECK(std::stod(rows[k].at("impact_speed_m_s")) == mine[k]->impact_speed);
      CHECK(std::stod(rows[k].at("largest_fraction")) == mine[k]->largest_fraction);
    }
  }

  // The one-run report of the same file: its speed bins hold the run's three plates.
  {
    FragmentsOptions fo;
    fo.run_file = out / "runs" / "v2.5_s1" / "run.h5";
    fo.report = out / "one_run";
    std::ostringstream fout, ferr;
    CHECK(fragments_command(fo, fout, ferr) == 1);  // --report needs --by-body
    CHECK(ferr.str().find("add --by-body") != std::string::npos);
    fo.by_body = true;
    fo.speed_bins = 2;
    REQUIRE(fragments_command(fo, fout, ferr) == 0);
    const auto bins = read_csv(out / "one_run" / "breakage_vs_speed.csv");
    REQUIRE(bins.size() == 2);
    CHECK(std::stoi(bins[0].at("plates")) + std::stoi(bins[1].at("plates")) == 3);
    CHECK(read_csv(out / "one_run" / "plates.csv").size() == 3);
    CHECK(fs::exists(out / "one_run" / "report.md"));
  }

  // Faster plates strike faster and break no less than the bands allow.
  REQUIRE(r.by_value.size() == 2);
  const auto& slow = r.by_value[0];
  const auto& fast = r.by_value[1];
  CHECK(slow.lower == 0.8);
  CHECK(fast.lower == 2.5);
  CHECK(slow.not_impacted == 0);
  CHECK(fast.not_impacted == 0);
  CHECK(fast.mean_speed > slow.mean_speed + 1.0);
  CHECK(fast.broken_interval.upper >= slow.broken_interval.lower);
  CHECK(fast.broken_share >= slow.broken_share);
  MESSAGE("broken share at 0.8 m/s: ", slow.broken_share, ", at 2.5 m/s: ", fast.broken_share);

  // Tables, HDF5, pictures and the report are where the report page says.
  CHECK(read_csv(out / "plates.csv").size() == 12);
  CHECK(read_csv(out / "runs.csv").size() == 4);
  CHECK(read_csv(out / "breakage_vs_value.csv").size() == 2);
  CHECK(fs::exists(out / "report.md"));
  const hid_t f = H5Fopen((out / "sweep.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  for (const char* g : {"/runs", "/plates", "/by_value", "/by_impact_speed"}) CHECK(H5Lexists(f, g, H5P_DEFAULT) > 0);
  H5Fclose(f);
  if (fs::exists("/usr/bin/gnuplot")) {
    std::ifstream png(out / "breakage_vs_speed.png", std::ios::binary);
    char magic[4] = {};
    png.read(magic, 4);
    CHECK(std::string(magic + 1, 3) == "PNG");
  }
}

TEST_CASE("a failing run is reported and the sweep goes on with the others") {
  // Copies 10 mm apart overlap at placement: that run fails (a SceneError inside the run), the
  // run at the scene's spacing ends normally.
  const fs::path out = fs::temp_directory_path() / "failing_sweep";
  fs::remove_all(out);
  SweepOptions o = small_sweep("body.shard.stream.spacing[0]=0.065,0.01", out, 1);
  o.sets.push_back("body.shard.stream.copies=2");
  o.sets.push_back("simulation.duration=0.002");
  std::ostringstream log;
  const SweepResult r = run_sweep(o, log);
  REQUIRE(r.runs.size() == 2);
  CHECK_FALSE(r.runs[0].failed());
  CHECK(r.runs[1].failed());
  CHECK(r.runs[1].error.find("overlap") != std::string::npos);
  CHECK(r.failed() == 1);
  CHECK(r.plates.size() == 2);
  const auto runs = read_csv(out / "runs.csv");
  REQUIRE(runs.size() == 2);
  CHECK(runs[1].at("ran") == "0");
  std::ifstream report(out / "report.md");
  const std::string page((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  CHECK(page.find("failed: ") != std::string::npos);
}
