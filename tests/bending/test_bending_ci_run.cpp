// The CI-size four-point bending beam through the whole pipeline (run_scene -> run.h5 ->
// analyse_bending_run): it must fail, in the constant-moment zone between the pins, into two
// major pieces, quasi-statically; eq. 14 on the beam's own deflection must give the network's
// own E (the curvature modulus between the pins) within 10 %.
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>

#include "shard/app/run_command.hpp"
#include "shard/bending/bending_run.hpp"

TEST_CASE("CI beam: brittle failure between the pins, two major fragments, quasi-static loading") {
  shard::RunOptions o;
  o.scene = std::filesystem::path(SHARD_SOURCE_DIR) / "scenes/four_point_bending_ci.toml";
  o.out_dir = "bending_ci_out";
  o.plugin_dirs = {std::filesystem::path(SHARD_BUILD_DIR) / "plugins"};
  o.threads = 1;
  o.quiet = true;
  std::ostringstream log;
  const auto summary = shard::run_scene(o, log);
  const auto r = shard::bending::analyse_bending_run(summary.output);
  CHECK(r.analysis.failed);
  REQUIRE(r.crack.found);
  CHECK(r.crack.between_pins);                        // |s| <= 40 mm
  CHECK(r.fragments.major >= 2);                      // the beam parted
  CHECK(r.quasi_static.max_kinetic_to_elastic < 0.05);  // measured 0.0017 at 10 mm/s
  // The run's own quasi-static figure uses the same rows (before the first break, load >= 20 % of
  // the peak), so it tells the same story as the bending report (it read 14.5 here when it
  // compared against the running peak and so counted the seating rows).
  CHECK(summary.max_kinetic_to_elastic < 0.05);
  // Local instrumentation: eq. 14 on the beam's own deflection under the pins against the
  // network's E from the curvature in the constant-moment zone (same packing, same run). The
  // tolerance is the packing's heterogeneity: E_curv measures the middle 64 mm only, and the
  // network E differs between packings of this beam by 7 % (sd, 4 seeds; 14 % on the default
  // beam, 5 seeds). Measured 1.038 here; 0.94-1.06 over 9 packings (docs/explanation/four-point-bending.md).
  REQUIRE(r.gauges.valid);
  CHECK(r.gauges.deflection_fit.r_squared > 0.99);
  CHECK(std::abs(r.gauges.youngs_modulus / r.gauges.curvature_modulus - 1) < 0.10);
  // The pin travel adds the Hertz indentation at pins and supports: a softer apparent E.
  CHECK(r.analysis.youngs_modulus < r.gauges.youngs_modulus);
  // A damage limit lets the local gauges read frames after isolated breaks (a resolved beam loses
  // single bonds long before it cracks). The frames are a superset; a few bonds more leave the
  // network's E where the packing tolerance above puts it.
  shard::bending::BendingOptions tolerant;
  tolerant.local_damage_limit = 0.01;
  const auto d = shard::bending::analyse_bending_run(summary.output, tolerant);
  CHECK(d.gauges.breaks_allowed == static_cast<std::size_t>(std::floor(0.01 * static_cast<double>(r.bonds))));
  REQUIRE(d.gauges.valid);
  CHECK(d.gauges.frames.size() > r.gauges.frames.size());  // measured 75 -> 110
  CHECK(std::abs(d.gauges.youngs_modulus / r.gauges.youngs_modulus - 1) < 0.10);
  CHECK(std::abs(d.gauges.curvature_modulus / r.gauges.curvature_modulus - 1) < 0.10);
  MESSAGE("local E ", r.gauges.youngs_modulus, " -> ", d.gauges.youngs_modulus, ", curvature E ",
          r.gauges.curvature_modulus, " -> ", d.gauges.curvature_modulus, ", frames ", r.gauges.frames.size(), " -> ",
          d.gauges.frames.size(), ", breaks allowed ", d.gauges.breaks_allowed);
  // A clean rise gets no warning about its stiffness fit; a ringing one (the seed beam's pins at
  // 20 mm/s without a ramp: R^2 0.25 over 10-40 % of F_max) does.
  CHECK(shard::bending::format_report(r).find("warning: the stiffness fit") == std::string::npos);
  auto ringing = r;
  ringing.analysis.fit.r_squared = 0.25;
  CHECK(shard::bending::format_report(ringing).find("warning: the stiffness fit explains only R^2 = 0.25") !=
        std::string::npos);
  CHECK(std::abs(r.geometry.span - 0.170) < 1e-9);
  CHECK(std::abs(r.geometry.pin_distance - 0.080) < 1e-9);
}
