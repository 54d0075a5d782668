// The measurement loop judged on hidden effects, end to end through the shard binary on
// the tiny bending beam. Each case hides something in synthetic measurements (packing seeds
// 1001-1003, not the model's 1-3; 2 % specimen scatter, 0.01 N load-cell noise, 0.005 N tare,
// 1 um displacement steps), then `shard diagnose` with the whole effect library must
//   - null case: say "adequate" and claim nothing;
//   - a library effect: name it (the confirmed verdict), with the right sign and order of size,
//     and `shard calibrate-effect --with` it must cut the NRMSE by >= 50 % without any regime
//     getting worse beyond noise;
//   - a seating toe no candidate models: say "unexplained structured residual".
// The cases share one work folder: the model side of every diagnosis (base, +5 % steps, effect
// signatures on seeds 1-3) is the same runs, simulated once and then read from the run cache.
// Slow (~100 simulations of 3-6 s, two at a time): see docs/explanation/diagnosis.md for the time.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>

#include "shard_cli.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kWork = fs::current_path() / "measure_hidden_work";
const std::string kScene = std::string(SHARD_SOURCE_DIR) + "/scenes/measurements/tiny_bending.toml";
const std::string kSensor = " --scatter 0.02 --force-noise 0.01 --force-offset 0.005 --displacement-step 1e-6";
const std::string kParams = " --param bond.youngs_modulus --param bond.critical_stress";

void shard(const std::string& args) { shard_test::run_shard(args, kWork); }
using nlohmann::json;
using shard_test::element_with;
using shard_test::read_document;
using shard_test::read_text;

// The documents' format versions this test reads (each command's kind of document).
constexpr int kDiagnoseVersion = 1, kCalibrateVersion = 1, kCompareVersion = 1;

// synth + diagnose; returns diagnose.json.
json diagnose_hidden(const std::string& tag, const std::string& hidden, const std::string& rates = "") {
  const fs::path meas = kWork / ("meas_" + tag), out = kWork / ("diag_" + tag);
  shard("synth --scene " + kScene + " --work " + kWork.string() + " --out " + meas.string() + kSensor + hidden +
        (rates.empty() ? "" : " --rates " + rates));
  shard("diagnose " + meas.string() + " --scene " + kScene + " --work " + kWork.string() + kParams + " --out " +
        out.string());
  return read_document(out / "diagnose.json", kDiagnoseVersion);
}

// A regime gets worse beyond noise when, after the calibration, its mean standardised residual
// is beyond noise and larger in size than before. A regime mean is read as one N(0, 1) score
// (comparison.hpp), and five regimes are judged at once: at a family-wise level of 5 % each one
// is beyond noise when |r| > z(1 - 0.05 / (2 x 5)) = 2.58 (Bonferroni). The comparison's own
// per-regime flag (|r| > 2) is the single-regime test; with five regimes and seed-estimated
// bands it is raised for one regime of a right model in about a quarter of the cases.
constexpr double kRegimeNoise = 2.58;

// Every regime the calibration reports ("toe", ... at one rate; "toe@0.02", ... at several; a
// regime empty on the grid is not listed), each entry "name": [before, after].
void check_no_regime_worse(const json& calibration) {
  int checked = 0;
  for (const auto& [name, before_after] : calibration.at("regimes").items()) {
    const double before = before_after.at(0), after = before_after.at(1);
    INFO("regime " << name << ": mean residual " << before << " -> " << after);
    CHECK_FALSE((std::abs(after) > kRegimeNoise && std::abs(after) > std::abs(before)));
    ++checked;
  }
  CHECK(checked >= 3);  // at least toe/elastic/peak exist on every curve the loop compares
}

struct Hidden {
  Hidden(std::string tag_, std::string synth_, std::string effect_, double truth_, double neutral_)
      : tag(std::move(tag_)), synth(std::move(synth_)), effect(std::move(effect_)), truth(truth_), neutral(neutral_) {}
  std::string tag, synth, effect;
  double truth = 0, neutral = 0;
  // The band of the diagnosis's linearised size over the truth, and calibrate-effect's budget.
  double size_low = 2.0 / 3.0, size_high = 1.5;
  int evaluations = 3;
  std::string rates;  // synth --rates; empty: the scene's pin speed
};

// The library effect must be the confirmed verdict; its linearised size within 2/3..3/2 of the
// truth (the signature is taken at the library's plausible size, not at the truth, and the
// packing noise of three specimens moves it); calibrate-effect must halve the NRMSE, and its
// fitted size must be within 2/3..3/2 of the truth.
void check_found_and_calibrated(const Hidden& h) {
  const json diagnosis = diagnose_hidden(h.tag, h.synth, h.rates);
  INFO(h.tag << ": " << diagnosis.dump());
  CHECK(diagnosis.at("verdict") == h.effect);  // implies "not adequate"
  // The estimate of the named effect's size from its confirmation refit.
  const double estimate = element_with(diagnosis.at("confirmations"), "name", h.effect).at("value");
  const double ratio = (estimate - h.neutral) / (h.truth - h.neutral);
  CHECK(ratio > h.size_low);
  CHECK(ratio < h.size_high);

  const fs::path out = kWork / ("cal_" + h.tag);
  // Three evaluations: the linearised start (cached from the diagnosis) and two BOBYQA steps; the
  // tutorial runs more (docs/tutorials/measurement-loop.md).
  // The spelling, `shard calibrate --with`, routed to calibrate-effect (command_routing.hpp).
  shard("calibrate " + (kWork / ("meas_" + h.tag)).string() + " --scene " + kScene + " --work " + kWork.string() +
        kParams + " --with " + h.effect + " --max-evaluations " + std::to_string(h.evaluations) + " --out " + out.string());
  const json cal = read_document(out / "calibrate.json", kCalibrateVersion);
  INFO(cal.dump());
  const double before = cal.at("nrmse_before"), after = cal.at("nrmse_after");
  CHECK(after <= 0.5 * before);
  const double fitted = (cal.at("value").get<double>() - h.neutral) / (h.truth - h.neutral);
  CHECK(fitted > 2.0 / 3.0);
  CHECK(fitted < 1.5);
  check_no_regime_worse(cal);
}

}  // namespace

TEST_CASE("null case: data from the base model itself are adequate and no effect is claimed") {
  const json diagnosis = diagnose_hidden("null", "");
  INFO(diagnosis.dump());
  CHECK(diagnosis.at("verdict") == "adequate");
  CHECK(diagnosis.at("p_value").get<double>() > 0.05);
  CHECK(diagnosis.at("confirmations").empty());  // nothing refit, nothing named
}

TEST_CASE("time compression: the quasi-static tiny beam at half the data's rate compares as at the data's rate") {
  // Null data at 0.02 m/s; the model at 0.01 m/s (--time-compression 0.5). The beam is
  // quasi-static at these rates (peak 2.547 / 2.540 N at 0.02 / 0.01 m/s, docs/explanation/diagnosis.md),
  // so the comparison's NRMSE may move by the packing noise of the rate change only: 1 % point.
  diagnose_hidden("null", "");  // the data (cached when the null case ran first)
  const fs::path meas = kWork / "meas_null";
  shard("compare " + meas.string() + " --scene " + kScene + " --work " + kWork.string() + " --out " +
        (kWork / "cmp_rate").string());
  shard("compare " + meas.string() + " --scene " + kScene + " --work " + kWork.string() +
        " --time-compression 0.5 --out " + (kWork / "cmp_half").string());
  const double at_rate = read_document(kWork / "cmp_rate" / "compare.json", kCompareVersion).at("nrmse");
  const double at_half = read_document(kWork / "cmp_half" / "compare.json", kCompareVersion).at("nrmse");
  CHECK(std::abs(at_half - at_rate) < 0.01);
  CHECK(read_text(kWork / "log.txt").find("time compression 0.5: the model loads at 0.01 m/s") != std::string::npos);
}

TEST_CASE("data of another test geometry are refused, naming both set-ups") {
  // The tiny beam's specimens (span 36 mm, pins 16 mm) against the main bending scene
  // (170 mm, 80 mm): an error before any run, unless --ignore-geometry.
  diagnose_hidden("null", "");
  const std::string main_scene = std::string(SHARD_SOURCE_DIR) + "/scenes/four_point_bending.toml";
  const fs::path log = kWork / "geometry.txt";
  const std::string cmd = std::string(SHARD_BUILD_DIR) + "/bin/shard compare " + (kWork / "meas_null").string() +
                          " --scene " + main_scene + " --work " + kWork.string() + " --out " +
                          (kWork / "cmp_geometry").string() + " > " + log.string() + " 2>&1";
  CHECK(std::system(cmd.c_str()) != 0);
  const std::string text = read_text(log);
  INFO(text);
  CHECK(text.find("span 36 mm and pin distance 16 mm") != std::string::npos);
  CHECK(text.find("span 170 mm and pin distance 80 mm") != std::string::npos);
  CHECK(text.find("--ignore-geometry") != std::string::npos);
  // synth read the tiny beam's set-up from its scene: supports and pins, and the packing's size.
  const std::string specimens = read_text(kWork / "meas_null" / "specimens.csv");
  CHECK(specimens.find(",0.036,0.016,0.02,") != std::string::npos);
  // ... and, as a lab notes them, the crack position and the fragments of every specimen (the
  // truth runs' own, from shard::bending), reported by compare but not judged by default.
  CHECK(specimens.find(",0.02,,") == std::string::npos);
  CHECK(fs::exists(kWork / "meas_null" / "fragments" / "sim_seed1001.csv"));
  const json cmp = read_document(kWork / "cmp_rate" / "compare.json", kCompareVersion);
  element_with(cmp.at("features"), "name", "crack_position");
  element_with(cmp.at("features"), "name", "fragment_x50");
}

TEST_CASE("hidden machine compliance 1e-4 m/N: named, sized, calibrated") {
  // A 5 N S-beam load cell deflects ~0.25 mm at full scale (5e-5 m/N); with the fixture's
  // seating and the crosshead drive, 1e-4 m/N is what a small-force frame measured at the
  // crosshead adds. The specimen's own compliance is ~4e-4 m/N: the frame is a quarter of it.
  check_found_and_calibrated({"compliance", " --machine-compliance 1e-4", "machine_compliance", 1e-4, 0});
  // The confirmation refit alone (linearised sizes, simulated) halves the base refit's NRMSE.
  const json diagnosis = read_document(kWork / "diag_compliance" / "diagnose.json", kDiagnoseVersion);
  const double base_nrmse = element_with(diagnosis.at("confirmations"), "name", "base refit").at("nrmse");
  const double with_nrmse = element_with(diagnosis.at("confirmations"), "name", "machine_compliance").at("nrmse");
  CHECK(with_nrmse <= 0.5 * base_nrmse);
}

TEST_CASE("hidden bond softening (ratio 3): named, sized, calibrated") {
  // Cemented bridges soften over a few times their elastic strain before they separate
  // (quasi-brittle cohesive laws of mortars and sinter necks: softening strain / peak strain
  // 2-5); 3 is the middle of that range.
  check_found_and_calibrated(
      {"softening", " --set bond.softening_ratio=3", "bond_softening", 3, 0});
}

TEST_CASE("hidden compression asymmetry (bond stiffness ratio 4): named, sized, calibrated") {
  // Granular and microcracked solids are bimodular: cracks and grain contacts close in
  // compression and open in tension; compressive/tensile modulus ratios 1.5-4 are reported for
  // sandstones and cemented sands. 4 is the upper end; at 2 the base refit of E_b and
  // sigma_crit absorbs it (docs/explanation/diagnosis.md).
  check_found_and_calibrated({"asymmetry", " --set bond.compression_stiffness_ratio=4",
                              "compression_asymmetry", 4, 1});
}

TEST_CASE("hidden bond viscosity (tau_v 5 ms, data at 0.02 and 0.1 m/s): named, sized, calibrated") {
  // A binder whose stress relaxes over milliseconds on this beam's compressed time scale: at
  // 0.1 m/s the peak comes after ~10 ms, twice tau_v, so the beam is ~25 % stiffer than at
  // 0.02 m/s. One rate cannot show it (E_b absorbs a rate-independent stiffening,
  // docs/explanation/diagnosis.md); two rates a factor 5 apart do. The arm saturates (maxwell_arm.hpp), so
  // the response is concave in tau_v and the signature, taken at the plausible 1 ms, extrapolates
  // 5x: the linearised size is biased low (measured 0.56 of the truth) and only its order is
  // asserted (1/2..3/2); the calibrated size must meet 2/3..3/2. BOBYQA needs more than three steps
  // on three free parameters here (20: NRMSE 15.4 % -> 7.2 %).
  Hidden h{"viscosity", " --set bond.viscosity_time=5e-3", "bond_viscosity", 5e-3, 0};
  h.size_low = 0.5;
  h.evaluations = 20;
  h.rates = "0.02,0.1";
  check_found_and_calibrated(h);
}

TEST_CASE("hidden frictionless supports on one set: the base fit takes them up, nothing is named") {
  // Free-turning support rollers (friction 0 against the grains' 0.67; the pins keep theirs)
  // lower the stiffness and the peak together, as a softer and weaker bond does: on one set
  // without a reference, E_b and sigma_crit absorb the difference, and the diagnosis must not
  // name an effect for it. Against a reference batch, whose base fit holds E_b and sigma_crit,
  // the contrast diagnosis can (docs/explanation/foreign-truth.md).
  const json diagnosis = diagnose_hidden("free_supports", " --set material_pair.beam.support.friction=0");
  INFO(diagnosis.dump());
  CHECK(diagnosis.at("verdict") == "adequate");
  CHECK(diagnosis.at("p_value").get<double>() > 0.05);
  CHECK(diagnosis.at("confirmations").empty());
}

TEST_CASE("a seating toe outside the library is an unexplained structured residual, not a wrong name") {
  // Rough sawn faces: the pins and rollers first close a gap of loose surface grains, a
  // hyperbolic closure w + g F / (F + F_h) (synthetic.hpp). g = 0.3 mm, F_h = 0.3 N (15 % of the
  // peak): the toe ASTM D790 tells the tester to compensate, on a soft 8 mm beam.
  const json diagnosis = diagnose_hidden("toe", " --seating-gap 3e-4 --seating-half-force 0.3");
  INFO(diagnosis.dump());
  CHECK(diagnosis.at("p_value").get<double>() < 0.05);  // the model does fail ...
  CHECK(diagnosis.at("verdict") == "unexplained structured residual");  // ... and nothing is named
}
