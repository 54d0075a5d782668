// Every JSON document the bending commands write -- `shard bending-rate-check` (rate_check.json),
// `shard bending` (<run>_bending.json) and `shard calibrate` (calibration.json and a report beside
// each run) -- loads with a strict parser (nlohmann's parse throws on nan and inf) and carries
// format_version 1 and the Shard version. The coarse beam keeps the four runs at seconds each.
#include <doctest/doctest.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shard/app/commands.hpp"
#include "shard/io/json.hpp"

namespace fs = std::filesystem;

namespace {

int run_command(const std::vector<std::string>& args) {
  CLI::App app;
  shard::CommandContext ctx;
  ctx.plugin_dirs = {fs::path(SHARD_BUILD_DIR) / "plugins"};
  shard::add_bending_command(app, ctx);
  std::vector<const char*> argv{"shard"};
  for (const auto& a : args) argv.push_back(a.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
  return ctx.exit_code;
}

// The file parsed strictly; fails the test naming the file when it is not JSON.
nlohmann::json load_strict(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j;
  CHECK_NOTHROW(j = nlohmann::json::parse(text.str()));
  return j;
}

std::vector<fs::path> json_files_under(const fs::path& folder) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(folder))
    if (e.path().extension() == ".json") out.push_back(e.path());
  return out;
}

void check_document(const fs::path& file) {
  INFO(file.string());
  const auto j = load_strict(file);
  REQUIRE(j.is_object());
  CHECK(j.at("format_version") == 1);
  CHECK(j.at("shard_version") == shard::io::shard_version());
}

}  // namespace

TEST_CASE("the bending commands write strict JSON documents with a format version") {
  const fs::path scene = fs::path(SHARD_SOURCE_DIR) / "scenes/four_point_bending_coarse.toml";
  for (const char* dir : {"json_rate_check", "json_report", "json_calibration"}) fs::remove_all(dir);

  // Exit 0 (passed) or 2 (failed the criteria) both write the document; 1 would be an error.
  const int rate = run_command({"bending-rate-check", scene.string(), "--threads", "1", "--out", "json_rate_check"});
  CHECK((rate == 0 || rate == 2));
  const auto rate_check = load_strict("json_rate_check/rate_check.json");
  check_document("json_rate_check/rate_check.json");

  fs::path run_file;
  for (const auto& e : fs::recursive_directory_iterator("json_rate_check/rate"))
    if (e.path().extension() == ".h5") run_file = e.path();
  REQUIRE(!run_file.empty());
  fs::create_directories("json_report");
  CHECK(run_command({"bending", run_file.string(), "--no-plot", "--json", "json_report/report.json"}) == 0);
  check_document("json_report/report.json");
  // The same run analysed the same way by both commands: the figure survives the text exactly.
  const auto report = load_strict("json_report/report.json");
  CHECK(report.at("force_max_N").get<double>() == rate_check.at("force_max_N")[0].get<double>());
  CHECK(report.at("force_max_N").get<double>() > 0);

  // A target E four times the scene's cannot be met in one run (exit 2, not converged); the
  // calibration and the run's report are written all the same.
  CHECK(run_command({"calibrate", scene.string(), "--target-E", "50e6", "--max-runs", "1", "--threads", "1", "--out",
                     "json_calibration"}) == 2);
  const auto calibration_files = json_files_under("json_calibration");
  CHECK(calibration_files.size() == 2);  // calibration.json and the run's <run>_bending.json
  for (const auto& file : calibration_files) check_document(file);
  const auto calibration = load_strict("json_calibration/calibration.json");
  CHECK(calibration.at("converged") == false);
  CHECK(calibration.at("runs").size() == 1);
  CHECK(calibration.at("target_force_max_N").is_null());  // no strength target given
}
