// `shard calibrate` on a real (coarse) beam: a run with known bond parameters gives the targets,
// a calibration started from Table I's parameters must meet them within 3 % in at most 20 runs.
// The same packing (seed) is used, so the targets are reachable by construction. ~30 s of CPU.
#include <doctest/doctest.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shard/app/commands.hpp"
#include "shard/app/run_command.hpp"
#include "shard/bending/bending_run.hpp"

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
  return cells;
}

}  // namespace

TEST_CASE("calibration of a coarse beam reaches E and F_max of a run with known parameters") {
  const auto scene = std::filesystem::path(SHARD_SOURCE_DIR) / "scenes/four_point_bending_coarse.toml";
  const std::filesystem::path plugins = std::filesystem::path(SHARD_BUILD_DIR) / "plugins";

  // The "measurement": E_b = 20 MPa, sigma_crit = 0.32 MPa (Table I: 12.8 and 0.24 MPa).
  shard::RunOptions truth;
  truth.scene = scene;
  truth.overrides = {{"bond.youngs_modulus", 20e6}, {"bond.critical_stress", 0.32e6}};
  truth.out_dir = "bending_calibration_truth";
  truth.plugin_dirs = {plugins};
  truth.threads = 1;
  truth.quiet = true;
  std::ostringstream log;
  const auto truth_report = shard::bending::analyse_bending_run(shard::run_scene(truth, log).output);
  REQUIRE(truth_report.analysis.failed);
  REQUIRE(truth_report.gauges.valid);
  const double target_e = truth_report.gauges.youngs_modulus, target_f = truth_report.analysis.force_max;

  CLI::App app;
  shard::CommandContext ctx;
  ctx.plugin_dirs = {plugins};
  shard::add_bending_command(app, ctx);
  std::filesystem::remove_all("bending_calibration_out");
  std::vector<std::string> args{"calibrate",    scene.string(), "--target-E", std::to_string(target_e),
                                "--target-Fmax", std::to_string(target_f), "--threads", "1",
                                "--out",        "bending_calibration_out"};
  std::vector<const char*> argv{"shard"};
  for (const auto& a : args) argv.push_back(a.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
  CHECK(ctx.exit_code == 0);

  std::ifstream csv("bending_calibration_out/calibration.csv");
  REQUIRE(csv);
  std::string header, line, last;
  std::getline(csv, header);
  int runs = 0;
  while (std::getline(csv, line))
    if (!line.empty()) last = line, ++runs;
  REQUIRE(runs >= 2);  // at least one stiffness and one strength run
  CHECK(runs <= 20);
  const auto cells = split(last);
  REQUIRE(cells.size() >= 8);
  CHECK(cells[1] == "strength");
  CHECK(cells[7] == "true");  // the final run broke the beam
  CHECK(std::abs(std::stod(cells[5]) / target_e - 1) <= 0.03);
  CHECK(std::abs(std::stod(cells[6]) / target_f - 1) <= 0.03);
  // The parameters found lie near the truth: E and F_max pin them down on this packing.
  CHECK(std::abs(std::stod(cells[2]) / 20e6 - 1) < 0.15);
  CHECK(std::abs(std::stod(cells[3]) / 0.32e6 - 1) < 0.15);
}
