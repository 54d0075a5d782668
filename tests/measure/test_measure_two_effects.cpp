// Two library effects hidden at once (issue 15): a diagnosis that names one effect at a time
// must go on stepwise. Synthetic data on the tiny bending beam (packing seeds 1001-1003, the
// model's 1-3; the sensor model of test_measure_hidden_effects) with machine compliance 1e-4 m/N
// and bond softening ratio 3 hidden together; `shard diagnose --max-effects 2` must name both in
// its path, and what remains after the second must be noise.
// Four candidates (--only) keep the runs to ~60 (~2 min on two idle cores): the two hidden ones
// and the two that ranked above softening in its single-effect case (compression asymmetry) or
// absorb a lower peak (Weibull strength).
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

const fs::path kWork = fs::current_path() / "measure_two_effects_work";
const std::string kScene = std::string(SHARD_SOURCE_DIR) + "/scenes/measurements/tiny_bending.toml";

void shard(const std::string& args) {
  fs::create_directories(kWork);
  const std::string cmd = std::string(SHARD_BUILD_DIR) + "/bin/shard " + args + " >> " + (kWork / "log.txt").string() + " 2>&1";
  INFO(cmd);
  REQUIRE(std::system(cmd.c_str()) == 0);
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

double number_after(const std::string& text, const std::string& key, std::size_t from = 0) {
  const auto at = text.find(key, from);
  INFO("missing " << key);
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + key.size()));
}

}  // namespace

TEST_CASE("machine compliance and bond softening hidden at once: both named, one after the other") {
  const fs::path meas = kWork / "meas", out = kWork / "diag";
  shard("synth --scene " + kScene + " --work " + kWork.string() + " --out " + meas.string() +
        " --scatter 0.02 --force-noise 0.01 --force-offset 0.005 --displacement-step 1e-6 --machine-compliance 1e-4"
        " --set bond.plugin=beam_bond_plus --set bond.softening_ratio=3");
  shard("diagnose " + meas.string() + " --scene " + kScene + " --work " + kWork.string() +
        " --param bond.youngs_modulus --param bond.critical_stress --only "
        "machine_compliance,bond_softening,compression_asymmetry,weibull_strength --refit 2 --max-effects 2 --out " +
        out.string());
  const std::string json = read(out / "diagnose.json");
  INFO(json);
  // Compliance first: it shifts the whole rise (measured: LM 40.6, its refit explains 75 % of the
  // excess, chi^2 74.3 -> 25.1, but p after 0.0015: kept, not named); softening second, on what
  // compliance leaves (chi^2 15.1 -> 3.5, p after 0.83: named).
  CHECK(json.find("\"verdict\": \"machine_compliance + bond_softening\"") != std::string::npos);
  const auto path = json.find("\"path\": [");
  REQUIRE(path != std::string::npos);
  const auto compliance = json.find("{\"effect\": \"machine_compliance\"", path);
  const auto softening = json.find("{\"effect\": \"bond_softening\"", path);
  REQUIRE(compliance != std::string::npos);
  REQUIRE(softening != std::string::npos);
  CHECK(compliance < softening);
  // The first step sizes compliance alone, before softening is known: its order must be right
  // (measured 0.89 of the truth); a factor 2 either way is the band of the single-effect test's
  // linearised sizes (2/3..3/2) widened for the second, unmodelled effect.
  const double c = number_after(json, "\"value\": ", compliance) / 1e-4;
  CHECK(c > 0.5);
  CHECK(c < 2.0);
  // Softening is sized at the second step with compliance re-sized along; the two trade off
  // (measured 3.9, the refit's bound of 3.9 plausible sizes, with compliance at 5.2e-5): only the
  // order is asserted, 2/3..3/2 of the truth 3 as in the single-effect test.
  const double s = number_after(json, "\"value\": ", softening) / 3;
  CHECK(s > 2.0 / 3.0);
  CHECK(s < 1.5);
  // The last step leaves noise (the name's meaning), the first did not (why it went on).
  CHECK(number_after(json, "\"p_after\": ", softening) > 0.05);
  CHECK(number_after(json, "\"p_after\": ", compliance) < 0.05);
  CHECK(json.find("\"named\": false", compliance) < softening);
}
