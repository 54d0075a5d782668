// The bad-input catalogue (docs/reference/errors.md): every file in bad_inputs/ is run through the real
// `shard` binary and must fail with exit code 1 and one line on stderr holding each of the
// file's "# expect:" fragments (file:line:column, what is wrong, what to do). Further cases need
// command-line arguments rather than a scene file.
#include <algorithm>
#include <fstream>

#include "reliability_fixtures.hpp"
#include "shard/hdf5_quiet.hpp"

using namespace shard;
using namespace shard::test;

namespace {

const std::filesystem::path kBadInputs = kSource / "tests" / "reliability" / "bad_inputs";

std::vector<std::string> expectations(const std::filesystem::path& scene) {
  std::vector<std::string> out;
  std::ifstream in(scene);
  const std::string tag = "# expect: ";
  for (std::string line; std::getline(in, line);)
    if (line.rfind(tag, 0) == 0) out.push_back(line.substr(tag.size()));
  return out;
}

// The error is the last line of stderr, one line: "shard: error: <file:line:col>: <what>; <what to
// do>" (progress lines may come before it).
std::string require_one_line_error(const Outcome& o) {
  CHECK(o.exit_code == 1);
  const auto start = o.err.rfind("shard: error: ");
  REQUIRE(start != std::string::npos);
  const std::string last = o.err.substr(start);
  CHECK(std::count(last.begin(), last.end(), '\n') == 1);
  CHECK(last.back() == '\n');
  return last;
}

}  // namespace

TEST_CASE("every scene in the bad-input catalogue fails with its message") {
  std::vector<std::filesystem::path> scenes;
  for (const auto& e : std::filesystem::directory_iterator(kBadInputs))
    if (e.path().extension() == ".toml") scenes.push_back(e.path());
  std::sort(scenes.begin(), scenes.end());
  REQUIRE(scenes.size() >= 25);
  const auto out = scratch("bad_inputs");
  for (const auto& scene : scenes) {
    CAPTURE(scene.filename().string());
    const auto expected = expectations(scene);
    REQUIRE_FALSE(expected.empty());
    // Run from the catalogue folder so the messages carry the bare file name.
    const Outcome o = run_shard("run '" + scene.filename().string() + "' --out '" + out.string() + "'", kBadInputs);
    CAPTURE(o.err);
    const std::string message = require_one_line_error(o);
    for (const auto& fragment : expected) CHECK(message.find(fragment) != std::string::npos);
  }
  // Nothing was written for a refused scene: the errors come before the run starts.
  CHECK_FALSE(std::filesystem::exists(out / "run.h5"));
}

TEST_CASE("command-line mistakes: missing scene, folder as scene, bad --set, restart without a run") {
  const auto dir = scratch("cli");
  Outcome o = run_shard("run nowhere.toml", dir);
  require_one_line_error(o);
  CHECK(o.err.find("nowhere.toml: cannot open the scene file") != std::string::npos);

  o = run_shard("run '" + kBadInputs.string() + "'", dir);
  require_one_line_error(o);
  CHECK(o.err.find("bad_inputs") != std::string::npos);

  o = run_shard("run '" + (kScenes / "crush_cube.toml").string() + "' --set contact.friction", dir);
  require_one_line_error(o);
  CHECK(o.err.find("expected section.key=value") != std::string::npos);

  o = run_shard("run '" + (kScenes / "crush_cube.toml").string() + "' --set contact.friction=30", dir);
  require_one_line_error(o);
  CHECK(o.err.find("'friction' = 30") != std::string::npos);
  CHECK(o.err.find("out of range [0, 10]") != std::string::npos);

  o = run_shard("run --restart run.h5", dir);
  require_one_line_error(o);
  CHECK(o.err.find("--restart run.h5: no such run file") != std::string::npos);

  std::ofstream(dir / "fake.h5") << "not hdf5";
  std::ofstream(dir / "fake.checkpoint.h5") << "not hdf5";
  o = run_shard("run --restart fake.h5", dir);
  require_one_line_error(o);
  CHECK(o.err.find("cannot read the checkpoint 'fake.checkpoint.h5'") != std::string::npos);

  o = run_shard("run", dir);
  require_one_line_error(o);
  CHECK(o.err.find("needs a scene file, or --restart run.h5") != std::string::npos);
}

TEST_CASE("plugins with a wrong ABI or that throw while registering are refused by name, the rest load") {
  const auto dir = scratch("plugins");
  const Outcome o = run_shard("--plugin-dir '" BAD_PLUGIN_DIR "' plugins", dir);
  CHECK(o.exit_code == 0);
  CHECK(o.err.find("shard_test_plugin_wrong_abi.so") != std::string::npos);
  CHECK(o.err.find("ABI") != std::string::npos);
  CHECK(o.err.find("shard_test_plugin_throws.so") != std::string::npos);
}

TEST_CASE("breakage on without a bond model runs, with a warning that nothing can break") {
  const auto dir = scratch("breakage_warning");
  std::string scene = read_text(kBadInputs / "negative_modulus.toml");
  scene.replace(scene.find("shear_modulus = -10e6"), 21, "shear_modulus = 10e6");
  scene.replace(scene.find("seed = 1"), 8, "seed = 1\nbreakage = true");
  scene = scene.substr(0, scene.find("# expect"));
  std::ofstream(dir / "scene.toml") << scene;
  const Outcome o = run_shard("run scene.toml --quiet", dir);
  CHECK(o.exit_code == 0);
  CHECK(o.err.find("warning: breakage = true but the scene has no [bond] section") != std::string::npos);
}

TEST_CASE("output that cannot be written fails at the start, naming the path") {
  const auto dir = scratch("unwritable");
  std::ofstream(dir / "a_file") << "x";
  const Outcome o = run_shard("run '" + (kScenes / "crush_cube.toml").string() + "' --out a_file/sub", dir);
  require_one_line_error(o);
  CHECK(o.err.find("a_file/sub") != std::string::npos);
  CHECK(o.err.find("Choose a folder you can write to") != std::string::npos);
  // Refused before the generator: its packing report ("scene ...: N particles") never came.
  CHECK(o.err.find("particles") == std::string::npos);
  CHECK(o.err.find("packing") == std::string::npos);
}

TEST_CASE("numeric options out of range are refused while parsing, in one line") {
  const auto dir = scratch("option_ranges");
  const std::string scene = "'" + (kScenes / "crush_cube.toml").string() + "'";
  for (const std::string threads : {"0", "-3"}) {
    CAPTURE(threads);
    const Outcome o = run_shard("run " + scene + " --threads " + threads, dir);
    CAPTURE(o.err);
    const std::string message = require_one_line_error(o);
    CHECK(message.find("--threads") != std::string::npos);
    CHECK(message.find("at least 1") != std::string::npos);
    CHECK(o.err.find("particles") == std::string::npos);  // nothing was generated
  }
  Outcome o = run_shard("run " + scene + " --checkpoint-every -1", dir);
  CHECK(require_one_line_error(o).find("--checkpoint-every") != std::string::npos);
  o = run_shard("bending-rate-check " + scene + " --threads 0", dir);
  CHECK(require_one_line_error(o).find("at least 1") != std::string::npos);
  o = run_shard("calibrate " + scene + " --max-runs 0", dir);
  CHECK(require_one_line_error(o).find("--max-runs") != std::string::npos);
  o = run_shard("calibrate " + scene + " --tolerance -0.1", dir);
  CHECK(require_one_line_error(o).find("--tolerance") != std::string::npos);
  // A CLI11 mistake of another kind (an unknown option) takes the same one-line form.
  o = run_shard("run " + scene + " --thread 2", dir);
  CHECK(require_one_line_error(o).find("--thread") != std::string::npos);
  // calibrate --with takes one effect or two different ones (a pair named by diagnose).
  o = run_shard("calibrate a b --reference a --with machine_compliance --with machine_compliance --scene " + scene, dir);
  CHECK(require_one_line_error(o).find("--with machine_compliance given twice") != std::string::npos);
  o = run_shard("calibrate a b --reference a --with x --with y --with z --scene " + scene, dir);
  CHECK(require_one_line_error(o).find("one effect or two at once") != std::string::npos);
  o = run_shard("--plugin-dir nowhere plugins", dir);  // was searched silently
  CHECK(require_one_line_error(o).find("nowhere") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "run.h5"));
}

TEST_CASE("files that are not run files: one line naming the file, no HDF5 error stack") {
  const auto dir = scratch("not_run_files");
  std::ofstream(dir / "notes.h5") << "not HDF5 at all";
  // An HDF5 file without Shard's layout (as a checkpoint is).
  {
    const QuietHdf5Errors quiet;
    const hid_t file = H5Fcreate((dir / "other.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(file >= 0);
    H5Fclose(file);
  }
  for (const std::string name : {"notes.h5", "other.h5"}) {
    for (const std::string command : {"fragments", "bending"}) {
      CAPTURE(command + " " + name);
      const Outcome o = run_shard(command + " " + name, dir);
      CAPTURE(o.err);
      const std::string message = require_one_line_error(o);
      CHECK(message.find(name) != std::string::npos);
      CHECK(o.err == message);  // nothing else on stderr: no "HDF5-DIAG" stack
      CHECK(o.err.find("HDF5-DIAG") == std::string::npos);
    }
  }
  // A folder where a run file goes.
  std::filesystem::create_directories(dir / "folder.h5");
  const Outcome o = run_shard("fragments folder.h5", dir);
  CHECK(require_one_line_error(o).find("folder.h5") != std::string::npos);
}

TEST_CASE("a disk that fills up mid-run is an error naming the file, never a success") {
  // A file-size limit (ulimit -f, in 1 KiB blocks) fails writes with EFBIG like a full disk.
  const auto dir = scratch("disk_full");
  const Outcome o = run_shard("run '" + (kScenes / "crush_cube.toml").string() + "'", dir, "ulimit -f 64 && ");
  CAPTURE(o.err);
  const std::string message = require_one_line_error(o);  // HDF5's driver message spans lines
  CHECK(message.find("run.") != std::string::npos);  // run.h5 or its checkpoint is named
  CHECK(message.find("File too large") != std::string::npos);
  CHECK(o.err.find("HDF5-DIAG") == std::string::npos);
  CHECK(o.err.find("done:") == std::string::npos);
}
