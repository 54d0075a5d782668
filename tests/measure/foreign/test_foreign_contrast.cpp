// The contrast diagnosis judged on foreign truth: measurement sets made by a
// model of another form than Shard's (tests/measure/foreign: linear-spring bonds with a force
// criterion, linear contacts, a finer packing; make_foreign_sets.sh), diagnosed with Shard's own
// tiny beam and effect library. Eight sets of 4 specimens: the reference, a null set (nothing
// different, other specimens), four with one library effect in foreign form, one with a
// seating toe that no library effect models, and one with two library effects at once. The
// contrast diagnosis must
//   - say "no difference" for the null set (no confident alarm),
//   - name the hidden effect in at least 3 of the 4 library cases,
//   - say "unexplained difference" for the toe,
//   - name both effects of the two-effect set, compliance sized within a
//     factor of 2 of the truth, and calibrating both at once must cut its contrast NRMSE by half,
//   - and `shard calibrate --reference --with` the named effect on a named set must cut that
//     set's contrast NRMSE by at least 50 %.
// Slow (the model's ~100 runs; the truth's 28 are test_foreign_sets'): see docs/explanation/diagnosis.md.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "../shard_cli.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kWork = fs::current_path() / "foreign_contrast_work";
const std::string kScene = std::string(SHARD_SOURCE_DIR) + "/scenes/measurements/tiny_bending.toml";
const std::string kParams = " --param bond.youngs_modulus --param bond.critical_stress";

using nlohmann::json;
using shard_test::element_with;
using shard_test::read_text;

// The format versions of the contrast form's documents (diagnose.json and calibrate.json of
// `diagnose SETS` and `calibrate SETS`), each read with the strict parser.
constexpr int kContrastDiagnoseVersion = 2, kContrastCalibrateVersion = 2;

}  // namespace

TEST_CASE("contrast diagnosis on foreign truth: null, four library effects, one outside, two at once") {
  fs::create_directories(kWork);
  // Made by test_foreign_sets (make_foreign_sets.sh), this test's ctest fixture.
  const fs::path sets = FOREIGN_SETS_DIR;
  REQUIRE(fs::exists(sets / "toe" / "specimens.csv"));
  std::string folders;
  for (const char* s : {"reference", "null", "compliance", "weibull", "softening", "asymmetry", "toe", "both"})
    folders += ' ', folders += (sets / s).string();
  const fs::path diag = kWork / "diagnose";
  shard_test::run_shard("diagnose" + folders + " --reference reference --scene " + kScene + " --work " +
                            (kWork / "model").string() + kParams + " --out " + diag.string(),
                        kWork);
  const json diagnosis = shard_test::read_document(diag / "diagnose.json", kContrastDiagnoseVersion);
  const auto set_result = [&](const std::string& set) -> const json& {
    return element_with(diagnosis.at("sets"), "name", set);
  };
  std::map<std::string, std::string> verdict;
  for (const char* s : {"null", "compliance", "weibull", "softening", "asymmetry", "toe", "both"})
    verdict[s] = set_result(s).at("verdict").get<std::string>();
  for (const auto& [set, v] : verdict) MESSAGE(set << ": " << v);

  CHECK(verdict["null"] == "no difference");
  CHECK(verdict["toe"] == "unexplained difference");
  // Two effects at once: machine compliance 2e-4 m/N and the foreign softening 1.5. The closest
  // single effect (compliance) takes most of the difference and leaves a remainder; the pair with
  // bond_softening explains it (six draws of these sets: both named in 6, compliance 1.76-2.17e-4
  // m/N; docs/explanation/diagnosis.md, "Lab data: contrasts across sets").
  CHECK(verdict["both"] == "machine_compliance + bond_softening");
  const double both_compliance = set_result("both").at("pair").at("values").at(0).get<double>();
  MESSAGE("both: machine_compliance " << both_compliance << " m/N (truth 2e-4)");
  CHECK(both_compliance > 1e-4);
  CHECK(both_compliance < 4e-4);
  // Both added at once, sized jointly on the two-set contrast: the error falls (measured on this
  // draw: 35.0 -> 5.5 %, compliance 1.49e-4 m/N, softening ratio 4.85).
  const fs::path cal_both = kWork / "calibrate_both";
  shard_test::run_shard("calibrate " + (sets / "reference").string() + " " + (sets / "both").string() +
                            " --reference reference --with machine_compliance --with bond_softening --scene " + kScene +
                            " --work " + (kWork / "model").string() + kParams + " --out " + cal_both.string(),
                        kWork);
  const json cb = shard_test::read_document(cal_both / "calibrate.json", kContrastCalibrateVersion);
  const double both_before = cb.at("nrmse_before").get<double>(), both_after = cb.at("nrmse_after").get<double>();
  MESSAGE("both: contrast NRMSE " << both_before << " -> " << both_after << " with both effects calibrated");
  CHECK(cb.at("effect") == "machine_compliance + bond_softening");
  CHECK(both_after <= 0.5 * both_before);
  // The outside effect gets no lead: its closest fit (machine_compliance, 42 % of T^2 on this draw)
  // takes far less than the 85 % of the difference that makes the report point to a library effect.
  const std::string md = read_text(diag / "diagnose.md");
  const auto toe_section = md.find("\n## toe");
  REQUIRE(toe_section != std::string::npos);
  CHECK(md.find("no library effect in the library's form explains it", toe_section) != std::string::npos);
  const std::map<std::string, std::string> hidden{{"compliance", "machine_compliance"},
                                                  {"weibull", "weibull_strength"},
                                                  {"softening", "bond_softening"},
                                                  {"asymmetry", "compression_asymmetry"}};
  // The calibration is asked of the named set whose contrast stands furthest above the noise (the
  // largest base contrast NRMSE): a contrast near the null set's NRMSE (its noise floor) cannot
  // fall by half whatever the model does.
  int named = 0;
  std::string calibrate_set;
  double largest = 0;
  for (const auto& [set, effect] : hidden)
    if (verdict[set] == effect) {
      ++named;
      const double nrmse = set_result(set).at("nrmse_base").get<double>();
      if (nrmse > largest) largest = nrmse, calibrate_set = set;
    }
  CHECK(named >= 3);

  REQUIRE_FALSE(calibrate_set.empty());
  const fs::path cal = kWork / "calibrate";
  shard_test::run_shard("calibrate " + (sets / "reference").string() + " " + (sets / calibrate_set).string() +
                            " --reference reference --with " + hidden.at(calibrate_set) + " --scene " + kScene +
                            " --work " + (kWork / "model").string() + kParams + " --out " + cal.string(),
                        kWork);
  const json c = shard_test::read_document(cal / "calibrate.json", kContrastCalibrateVersion);
  const double before = c.at("nrmse_before").get<double>(), after = c.at("nrmse_after").get<double>();
  MESSAGE(calibrate_set << ": contrast NRMSE " << before << " -> " << after);
  CHECK(after <= 0.5 * before);
}

TEST_CASE("the base fit moves bond.poisson_ratio on foreign truth: the post-peak form error falls") {
  // E_b and sigma_crit fit the reference's stiffness, peak force and peak displacement; the
  // lattice's bonds are stiffer in shear relative to their normal stiffness than the scene's
  // (poisson 0.25), which shows after the peak only (docs/explanation/diagnosis.md: poisson 0.4 by hand took
  // the form error from 8.0 to 3.5 %, the post-peak regime from -4.2 to -0.1 sigma). With the
  // post-peak regime among its targets, a base fit of the three must find it.
  fs::create_directories(kWork);
  const fs::path sets = FOREIGN_SETS_DIR;
  REQUIRE(fs::exists(sets / "null" / "specimens.csv"));
  auto fit = [&](const std::string& params, const std::string& out) {
    // Appended piecewise (GCC 12's false -Wrestrict on long operator+ chains).
    std::string args = "diagnose ";
    args += (sets / "reference").string();
    args += ' ';
    args += (sets / "null").string();
    args += " --reference reference --scene ";
    args += kScene;
    args += " --work ";
    args += (kWork / "model").string();
    args += params;
    args += " --only machine_compliance --confirm 0 --out ";
    args += (kWork / out).string();
    shard_test::run_shard(args, kWork);
    return shard_test::read_document(kWork / out / "diagnose.json", kContrastDiagnoseVersion);
  };
  const json two = fit(kParams, "base_two");
  std::string three_params = kParams;
  // tiny_bending.toml leaves poisson_ratio at beam_bond's default; a base parameter is read from the scene.
  three_params += " --param bond.poisson_ratio --set bond.poisson_ratio=0.25";
  const json three = fit(three_params, "base_three");
  const double nrmse_two = two.at("form_error_nrmse").get<double>();
  const double nrmse_three = three.at("form_error_nrmse").get<double>();
  const double poisson = three.at("base").at("bond.poisson_ratio").get<double>();
  const double u_poisson = three.at("base_uncertainty").at("bond.poisson_ratio").get<double>();
  MESSAGE("form error NRMSE " << nrmse_two << " -> " << nrmse_three << ", poisson_ratio " << poisson << " +- "
                              << u_poisson);
  CHECK(three.at("base_form_targets") == true);
  CHECK(two.at("base_form_targets") == false);
  // Measured: 6.7 % -> 2.6 % (the sets' noise floor against their own model is 2.8 %), poisson_ratio
  // 0.125 +- 0.028 with sigma_crit 7 % higher: the fit found another route than the by-hand
  // poisson 0.4 (one parameter moved at a time), so the direction is not asserted, the move is.
  CHECK(u_poisson > 0);
  CHECK(std::abs(poisson - 0.25) > 2 * u_poisson);  // the move stands above its own uncertainty
  CHECK(nrmse_three < 0.75 * nrmse_two);
}
