// Test conditions as the lab ran them, end to end through the shard binary on the tiny bending
// beam: `shard synth` records like a lab with a seating preload, a known zero offset and a 1-cos
// pin ramp at two rates; `shard compare` then runs the model with the same ramp, zeroes its
// curves at the same preload, compares both rates in one go (one history entry), and says that
// the model is dynamic at the faster rate. The model side uses the truth's packing seeds, so when
// it runs and records the test as the lab did its runs are the truth's runs (the same cache
// keys) and the NRMSE is zero to rounding; leaving the ramp or the preload out of the metadata
// must then show. Eight runs of ~3 s (slow label).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "shard_cli.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kWork = fs::current_path() / "measure_lab_conditions_work";
const std::string kScene = std::string(SHARD_SOURCE_DIR) + "/scenes/measurements/tiny_bending.toml";
const std::string kShard = std::string(SHARD_BUILD_DIR) + "/bin/shard ";
const std::string kModel = " --scene " + kScene + " --work " + kWork.string() + " --first-seed 1001 --seeds 2";

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs shard with `args`; returns its exit status and leaves stdout + stderr in `output`.
int shard(const std::string& args, std::string& output) {
  fs::create_directories(kWork);
  const fs::path log = kWork / "last.txt";
  const int status = std::system((kShard + args + " > " + log.string() + " 2>&1").c_str());
  output = read(log);
  return status;
}

void shard_ok(const std::string& args) {
  std::string output;
  const int status = shard(args, output);
  INFO(args << "\n" << output);
  REQUIRE(status == 0);
}

std::size_t lines(const fs::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += !line.empty();
  return n;
}

// compare.json's and history.jsonl's format versions this test reads.
constexpr int kCompareVersion = 1, kHistoryVersion = 1;

// The last model version of history.jsonl, one JSON object a line, read with the strict parser.
nlohmann::json last_history_entry(const fs::path& p) {
  std::ifstream in(p);
  std::string last;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) last = line;
  INFO(p.string() << ": " << last);
  nlohmann::json entry;
  REQUIRE_NOTHROW(entry = nlohmann::json::parse(last));
  CHECK(entry.at("format_version") == kHistoryVersion);
  return entry;
}

// A copy of the measurement folder `from` with metadata.toml's lines that start with `key` removed.
// (String search, not <regex>: GCC 12 warns falsely inside <regex> at -O1 with the sanitizers.)
fs::path without(const fs::path& from, const std::string& name, const std::string& key) {
  const fs::path to = kWork / name;
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
  std::istringstream in(read(from / "metadata.toml"));
  std::ofstream out(to / "metadata.toml");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key, 0) != 0) out << line << "\n";
  return to;
}

const fs::path kLab = kWork / "lab";

void synth_lab() {
  if (fs::exists(kLab / "specimens.csv")) return;
  shard_ok("synth --scene " + kScene + " --work " + kWork.string() + " --out " + kLab.string() +
           " --seeds 2 --rates 0.02,0.04 --seating-preload 0.2 --zero-offset 0.03 --ramp 1-cos --ramp-time 0.005 "
           "--grain-size 0.0023 --fragment-size-threshold 0.001 --notes \"tiny beam, lab-like\"");
}

}  // namespace

TEST_CASE("synth records like the lab: zero at the preload, the offset on every force, the conditions in metadata") {
  synth_lab();
  const std::string meta = read(kLab / "metadata.toml");
  INFO(meta);
  for (const char* line : {"seating_preload = 0.2", "zero_offset = 0.03", "ramp = \"1-cos\"", "ramp_time = 0.005",
                           "grain_size = 0.0023", "fragment_size_threshold = 0.001", "notes = \"tiny beam, lab-like\""})
    CHECK(meta.find(line) != std::string::npos);
  // Every curve starts at t = 0, d = 0 with the load cell reading the preload plus its offset.
  std::size_t curves = 0;
  for (const auto& f : fs::directory_iterator(kLab / "curves")) {
    std::istringstream in(read(f.path()));
    std::string header, first;
    std::getline(in, header);
    std::getline(in, first);
    CHECK(first.rfind("0,0,0.23,", 0) == 0);
    ++curves;
  }
  CHECK(curves == 4);
}

TEST_CASE("compare runs the model as the lab ran it, every rate in one go, and warns that it is dynamic") {
  synth_lab();
  const std::size_t before = fs::exists(kWork / "history.jsonl") ? lines(kWork / "history.jsonl") : 0;
  shard_ok("compare " + kLab.string() + kModel + " --out " + (kWork / "cmp_lab").string());
  const nlohmann::json json = shard_test::read_document(kWork / "cmp_lab" / "compare.json", kCompareVersion);
  INFO(json.dump());
  CHECK(json.at("rates") == nlohmann::json::array({0.02, 0.04}));
  // The truth's own runs: zero to rounding (the curves are written to 9 digits, NRMSE < 1e-6).
  CHECK(json.at("nrmse").get<double>() < 1e-6);
  CHECK(lines(kWork / "history.jsonl") == before + 1);  // both rates, one model version
  const nlohmann::json entry = last_history_entry(kWork / "history.jsonl");
  CHECK(entry.at("command") == "compare");
  // The entry holds this comparison's NRMSE: relative, since it is below 1e-6 here, and <= so
  // that an exact 0 matches too.
  const double nrmse = json.at("nrmse").get<double>();
  CHECK(std::abs(entry.at("nrmse").get<double>() - nrmse) <= 1e-5 * nrmse);
  // 0.04 m/s is twice the scene's 0.02 m/s pin speed.
  // "is dynamic" only when the energy ratio is above the bound; a faster rate alone says "may be".
  const std::string warning = json.at("dynamic_warning");
  const bool energetic = warning.find("(above the quasi-static bound") != std::string::npos;
  CHECK(warning.rfind(std::string("the model ") + (energetic ? "is" : "may be") + " dynamic at the data's rate", 0) == 0);
  CHECK(warning.find("2x faster than the 20 mm/s the scene was checked at") != std::string::npos);
  CHECK(read(kWork / "cmp_lab" / "compare.md").find(std::string("**Warning.** the model ") +
                                                     (energetic ? "is" : "may be") + " dynamic") != std::string::npos);

  // Without the ramp the model's pins start at full speed: a different curve (4.3 % measured).
  const fs::path no_ramp = without(kLab, "no_ramp", "ramp");
  shard_ok("compare " + no_ramp.string() + kModel + " --out " + (kWork / "cmp_no_ramp").string());
  CHECK(shard_test::read_document(kWork / "cmp_no_ramp" / "compare.json", kCompareVersion).at("nrmse").get<double>() > 0.01);
  // Without the preload the model's curves keep their toe below 0.2 N and another zero.
  const fs::path no_preload = without(kLab, "no_preload", "seating_preload");
  shard_ok("compare " + no_preload.string() + kModel + " --out " + (kWork / "cmp_no_preload").string());
  CHECK(shard_test::read_document(kWork / "cmp_no_preload" / "compare.json", kCompareVersion).at("nrmse").get<double>() >
        0.01);
}

TEST_CASE("a specimen of another width is refused, and a scene without effects.toml says what the file is") {
  synth_lab();
  // 12 mm wide specimens against the 8 mm beam (spheres up to 2.6 mm: beyond 2 % and a diameter).
  const fs::path wide = kWork / "wide";
  fs::remove_all(wide);
  fs::copy(kLab, wide, fs::copy_options::recursive);
  std::string specimens = read(kLab / "specimens.csv");
  // The first width (7.9x mm) becomes 12 mm.
  const auto width = specimens.find(",0.0079");
  REQUIRE(width != std::string::npos);
  specimens.replace(width, specimens.find(',', width + 1) - width, ",0.012");
  std::ofstream(wide / "specimens.csv") << specimens;
  std::string output;
  CHECK(shard("compare " + wide.string() + kModel + " --out " + (kWork / "cmp_wide").string(), output) != 0);
  INFO(output);
  CHECK(output.find("width 12 mm") != std::string::npos);
  CHECK(output.find("--ignore-geometry") != std::string::npos);

  // The scene copied elsewhere without its effect library.
  const fs::path alone = kWork / "scene_alone";
  fs::create_directories(alone);
  fs::copy_file(kScene, alone / "tiny_bending.toml", fs::copy_options::overwrite_existing);
  CHECK(shard("diagnose " + kLab.string() + " --scene " + (alone / "tiny_bending.toml").string() + " --work " +
                  kWork.string() + " --param bond.youngs_modulus --out " + (kWork / "diag_alone").string(),
              output) != 0);
  INFO(output);
  CHECK(output.find((alone / "effects.toml").string() + ": the candidate-effect library") != std::string::npos);
  CHECK(output.find("pass --effects FILE") != std::string::npos);
}
