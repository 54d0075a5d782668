// The measurement loop's run pool with each run in a worker process (`shard run-worker`): a run
// whose plugin segfaults is one failed run, reported with its signal, its scene, its overrides and
// its seed; the other runs finish, and their curves, quasi-static ratios and fractures are the
// ones a pool of threads gives without the crashing run, to the last digit of the cache. The
// cache fills as without isolation: a second pass starts no run.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "measure_runner.hpp"

namespace fs = std::filesystem;
using namespace shard;

namespace {

const fs::path kTinyBeam = fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/tiny_bending.toml";

// The tiny beam to 0.4 mm of pin travel (past its elastic part: ~1 s on one core).
RunRequest tiny(long seed, SceneOverrides extra = {}) {
  RunRequest r{kTinyBeam, {{"stop.max_displacement", 4e-4}}, seed, true};
  r.overrides.insert(r.overrides.end(), extra.begin(), extra.end());
  return r;
}

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  return dir;
}

// A sanitizer build's shard would catch the SEGV itself and exit with 1: the workers this test
// starts leave the signal to the kernel, as a plain build does.
void leave_segv_to_the_kernel() {
  const char* previous = std::getenv("ASAN_OPTIONS");
  std::string options = previous ? previous : "";
  if (!options.empty()) options += ":";
  options += "handle_segv=0";
  setenv("ASAN_OPTIONS", options.c_str(), 1);
}

}  // namespace

TEST_CASE("an isolated pool: the segfaulting run fails alone, named by its signal; the others are unchanged") {
  leave_segv_to_the_kernel();
  const std::vector<fs::path> plugin_dirs{SEGFAULT_PLUGIN_DIR};
  const SceneOverrides crash{{"bond.segfault_after", 200.0}};
  const std::vector<RunRequest> with_crash{tiny(1), tiny(2), tiny(1, crash), tiny(3)};
  const std::vector<RunRequest> without{tiny(1), tiny(2), tiny(3)};

  RunPool isolated(fresh("isolated_pool"), plugin_dirs, 2);
  isolated.isolate_runs({SHARD_PROGRAM, {"run-worker"}});
  std::ostringstream log;
  const auto results = isolated.try_run(with_crash, log);
  INFO(log.str());
  REQUIRE(results.size() == 4);
  CHECK(isolated.runs_started() == 4);

  const RunOutcome& crashed = results[2];
  REQUIRE(crashed.failed());
  CAPTURE(crashed.failure);
  CHECK(crashed.failure.find("SIGSEGV") != std::string::npos);
  CHECK(crashed.failure.find("tiny_bending.toml") != std::string::npos);
  CHECK(crashed.failure.find("seed 1") != std::string::npos);
  CHECK(crashed.failure.find("bond.segfault_after=200") != std::string::npos);
  CHECK_FALSE(fs::exists(isolated.work_dir() / "cache" / (crashed.key + ".run")));

  RunPool threads(fresh("thread_pool"), plugin_dirs, 2);
  const auto reference = threads.try_run(without, log);
  const std::size_t pool_index[] = {0, 1, 3};
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const RunOutcome& r = results[pool_index[k]];
    const RunOutcome& ref = reference[k];
    CAPTURE(k);
    REQUIRE_FALSE(r.failed());
    REQUIRE_FALSE(ref.failed());
    CHECK(r.key == ref.key);  // the same resolved scene, so the same cache entry
    REQUIRE(r.curve.size() > 50);
    CHECK(r.curve.time == ref.curve.time);
    CHECK(r.curve.displacement == ref.curve.displacement);
    CHECK(r.curve.force == ref.curve.force);
    CHECK(r.kinetic_to_elastic == ref.kinetic_to_elastic);
    CHECK(r.crack_position == ref.crack_position);
    CHECK(r.fragment_sizes == ref.fragment_sizes);
  }
  // The seeds differ, so do the curves: the comparison above can tell runs apart.
  CHECK(results[0].curve.force != results[1].curve.force);

  // A second pass finds every finished run in the cache and starts only the crashing one again.
  const auto again = isolated.try_run(with_crash, log);
  CHECK(isolated.runs_started() == 5);
  CHECK(again[0].cached);
  CHECK(again[3].cached);
  CHECK(again[0].curve.force == results[0].curve.force);
  CHECK(again[2].failed());
}
