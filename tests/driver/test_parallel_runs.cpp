// Runs on worker threads in one process: a run that blows up is reported as failed with its
// message and the other runs finish, with the same result as when run alone.
#include <doctest/doctest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "driver_fixtures.hpp"
#include "shard/driver/numerical_health.hpp"
#include "shard/driver/parallel_runs.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/stop_rules.hpp"

using namespace shard;
using namespace shard::driver;
using shard::test::kTinyBeam;
using shard::test::plugins;
using shard::test::scratch;

namespace {

// The tiny beam to 0.2 mm of pin travel, with `overrides` on top.
RunResult tiny_run(const std::string& name, SceneOverrides overrides) {
  MaxDisplacementStop stop;
  RunSpec spec;
  spec.scene = kTinyBeam;
  spec.out_dir = scratch(name);
  spec.threads = 1;
  spec.overrides = {{"stop.max_displacement", 2e-4}};
  spec.overrides.insert(spec.overrides.end(), overrides.begin(), overrides.end());
  return run(spec, plugins(), {&stop});
}

}  // namespace

TEST_CASE("a pool of runs: the blown-up one is reported failed, the others finish as they do alone") {
  const RunResult alone = tiny_run("alone", {{"simulation.seed", std::int64_t{2}}});
  // Twenty times the automatic step is past every critical step: the health watch stops it.
  const double unstable_dt = 20 * alone.dt;
  const std::vector<SceneOverrides> jobs{{{"simulation.seed", std::int64_t{1}}},
                                         {{"simulation.seed", std::int64_t{1}}, {"simulation.dt", unstable_dt}},
                                         {{"simulation.seed", std::int64_t{2}}},
                                         {{"simulation.seed", std::int64_t{3}}}};
  std::vector<RunResult> results(jobs.size());
  std::vector<std::size_t> reported;
  const auto errors = run_in_parallel(
      jobs.size(), 2, [&](std::size_t i) { results[i] = tiny_run("pool_" + std::to_string(i), jobs[i]); },
      [&](std::size_t i, const std::string&) { reported.push_back(i); });
  REQUIRE(errors.size() == jobs.size());
  CHECK(std::set<std::size_t>(reported.begin(), reported.end()) == std::set<std::size_t>{0, 1, 2, 3});
  CHECK(errors[0].empty());
  CHECK(errors[2].empty());
  CHECK(errors[3].empty());
  CAPTURE(errors[1]);
  CHECK(errors[1].find("the run blew up") != std::string::npos);
  // Determinism across threads: the pool's seed-2 run is the lone run, bit for bit.
  CHECK(results[2].steps == alone.steps);
  CHECK(results[2].curve.force == alone.curve.force);
  CHECK(results[2].curve.displacement == alone.curve.displacement);
  CHECK(results[0].steps > 0);
  CHECK(results[3].steps > 0);
}

TEST_CASE("whatever a run throws is its failure; a failing report counts as the run's failure") {
  const auto errors = run_in_parallel(
      3, 3,
      [](std::size_t i) {
        if (i == 0) throw std::runtime_error("bad input of run 0");
        if (i == 1) throw 42;  // not a std::exception
      },
      [](std::size_t i, const std::string& error) {
        if (i == 2 && error.empty()) throw std::runtime_error("cannot write the cache of run 2");
      });
  CHECK(errors[0] == "bad input of run 0");
  CHECK(errors[1].find("no std::exception") != std::string::npos);
  CHECK(errors[2] == "cannot write the cache of run 2");
}
