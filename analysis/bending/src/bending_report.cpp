// The bending report as text for the terminal and as JSON for scripts.
#include <fmt/format.h>

#include "shard/bending/bending_run.hpp"
#include "shard/io/json.hpp"

namespace shard::bending {

std::string format_report(const BendingReport& r) {
  const auto& g = r.geometry;
  const auto& a = r.analysis;
  std::string s;
  s += fmt::format("four-point bending: {}\n", r.run.string());
  s += fmt::format("  set-up: span {:.1f} mm, pin distance {:.1f} mm, width {:.2f} mm, height {:.2f} mm ({})\n",
                   1e3 * g.span, 1e3 * g.pin_distance, 1e3 * g.width, 1e3 * g.height, r.geometry_source);
  s += fmt::format("  specimen: {} particles, {} bonds, mean diameter {:.3f} mm, L/d = {:.1f} (length), "
                   "{:.1f} (smallest side)\n",
                   r.particles, r.bonds, 1e3 * r.mean_diameter, r.length / r.mean_diameter,
                   std::min(g.width, g.height) / r.mean_diameter);
  s += fmt::format("  bonds: E_b = {:.4g} MPa, sigma_crit = {:.4g} MPa, breakage {}\n", 1e-6 * r.bond.youngs_modulus,
                   1e-6 * r.bond.critical_stress, r.breakage ? "on" : "off");
  s += fmt::format("  stiffness k = {:.5g} N/mm (fit {:.0f}-{:.0f} % of F_max, {} rows, R^2 = {:.5f}), onset w0 = {:.4f} mm\n",
                   1e-3 * a.stiffness, 100 * a.fit_low, 100 * a.fit_high, a.fit.points, a.fit.r_squared, 1e3 * a.onset);
  // A rise that oscillates (pins started at speed without a ramp: the beam rings) or breaks within
  // the window is no line; eq. 14 on it reads the ringing, not the beam.
  if (a.fit.points >= 3 && a.fit.r_squared < 0.9)
    s += fmt::format("  warning: the stiffness fit explains only R^2 = {:.2f} of the rise: the load oscillates or breaks "
                     "within {:.0f}-{:.0f} % of F_max. Widen the window (--fit-high 1.0 averages a ringing beam), or "
                     "ramp the pins (wall.NAME.ramp = \"1-cos\", ramp_time over a few periods) and run again\n",
                     a.fit.r_squared, 100 * a.fit_low, 100 * a.fit_high);
  s += fmt::format("  F_max = {:.5g} N at w_s,max = {:.4f} mm (from onset){}; mean over {:.0f} um of travel: at most "
                   "{:.5g} N\n",
                   a.force_max, 1e3 * a.deflection_at_peak, a.failed ? ", then failed" : ", no failure (force did not drop)",
                   1e6 * a.peak_window, a.force_max_smoothed);
  s += fmt::format("  E (eq. 14, fitted stiffness) = {:.4g} MPa; secant at F_max = {:.4g} MPa\n", 1e-6 * a.youngs_modulus,
                   1e-6 * a.youngs_modulus_secant);
  s += fmt::format("  sigma_b (eq. 15) at F_max = {:.4g} MPa; {} bonds broken up to F_max\n", 1e-6 * a.flexural_strength,
                   r.breaks_before_peak);
  if (r.crack.found)
    s += fmt::format("  crack at s = {:+.1f} mm from the centre ({} of {} breaks within {:.1f} mm; IQR of all breaks "
                     "{:.1f} mm): {} the pins (+-{:.0f} mm)\n",
                     1e3 * r.crack.position, r.crack.cluster_breaks, r.crack.breaks, 1e3 * r.crack.window,
                     1e3 * r.crack.spread, r.crack.between_pins ? "between" : "OUTSIDE", 0.5e3 * g.pin_distance);
  else
    s += "  crack: no bond broke\n";
  std::string fr;
  for (double m : r.fragments.major_mass_fractions) fr += fmt::format("{}{:.1f} %", fr.empty() ? "" : ", ", 100 * m);
  s += fmt::format("  fragments at t = {:.4g} s: {} in all, {} holding >= 5 % of the mass ({})\n", r.fragments.frame_time,
                   r.fragments.count, r.fragments.major, fr);
  s += fmt::format("  network: Voigt (affine, upper bound) E = {:.4g} MPa, nu = {:.3f}; Timoshenko shear adds {:.1f} % "
                   "to the deflection under a pin\n",
                   1e-6 * r.voigt.youngs_modulus, r.voigt.poisson_ratio, 100 * r.shear_correction);
  const auto& lg = r.gauges;
  const std::string first_break =
      lg.breaks_allowed == 0 ? std::string("the first break") : fmt::format("break {}", lg.breaks_allowed + 1);
  if (lg.valid) {
    s += fmt::format("  local instrumentation ({} frames in the fit window of {} before {}): beam deflection under the pins "
                     "k_local = {:.5g} N/mm (R^2 {:.4f}) -> E (eq. 14) = {:.4g} MPa\n",
                     lg.fit_frames, lg.frames.size(), first_break, 1e-3 * lg.stiffness, lg.deflection_fit.r_squared,
                     1e-6 * lg.youngs_modulus);
    s += fmt::format("    curvature between the pins: E = M / (kappa I) = {:.4g} MPa (R^2 {:.4f}); beam theory on it "
                     "(eq. 14 + shear) predicts k_local = {:.5g} N/mm: measured / predicted = {:.3f}\n",
                     1e-6 * lg.curvature_modulus, lg.moment_fit.r_squared, 1e-3 * r.predicted_local_stiffness,
                     r.predicted_local_stiffness > 0 ? lg.stiffness / r.predicted_local_stiffness : 0.0);
    s += fmt::format("    pin travel / beam deflection: E (eq. 14, pins) / E (eq. 14, local) = {:.3f} (the rest is "
                     "contact indentation at pins and supports)\n",
                     a.youngs_modulus / lg.youngs_modulus);
  } else {
    s += fmt::format("  local instrumentation: {} frames before {}, {} in the fit window: too few "
                     "(output.frame_interval smaller, or --local-damage-limit)\n",
                     lg.frames.size(), first_break, lg.fit_frames);
  }
  s += fmt::format("  quasi-static: loading {:.4g} mm/s, {:.3g} s to F_max, kinetic/elastic energy <= {:.3g} before damage\n",
                   1e3 * r.quasi_static.loading_speed, r.quasi_static.load_time, r.quasi_static.max_kinetic_to_elastic);
  return s;
}

io::Json report_json(const BendingReport& r) {
  const auto& g = r.geometry;
  const auto& a = r.analysis;
  io::Json j = io::json_document(kBendingReportFormat);
  j["run"] = r.run.string();
  j["span_m"] = g.span;
  j["pin_distance_m"] = g.pin_distance;
  j["width_m"] = g.width;
  j["height_m"] = g.height;
  j["particles"] = r.particles;
  j["bonds"] = r.bonds;
  j["mean_diameter_m"] = r.mean_diameter;
  j["length_m"] = r.length;
  j["bond_youngs_modulus_Pa"] = r.bond.youngs_modulus;
  j["bond_critical_stress_Pa"] = r.bond.critical_stress;
  j["breakage"] = r.breakage;
  j["stiffness_N_per_m"] = a.stiffness;
  j["fit_r_squared"] = a.fit.r_squared;
  j["fit_points"] = a.fit.points;
  j["onset_m"] = a.onset;
  j["force_max_N"] = a.force_max;
  j["force_max_smoothed_N"] = a.force_max_smoothed;
  j["deflection_at_peak_m"] = a.deflection_at_peak;
  j["failed"] = a.failed;
  j["youngs_modulus_Pa"] = a.youngs_modulus;
  j["youngs_modulus_secant_Pa"] = a.youngs_modulus_secant;
  j["flexural_strength_Pa"] = a.flexural_strength;
  j["crack_found"] = r.crack.found;
  j["crack_position_m"] = r.crack.position;
  j["crack_between_pins"] = r.crack.between_pins;
  j["crack_breaks"] = r.crack.cluster_breaks;
  j["breaks"] = r.crack.breaks;
  j["fragments"] = r.fragments.count;
  j["major_fragments"] = r.fragments.major;
  j["major_mass_fractions"] = r.fragments.major_mass_fractions;
  j["voigt_youngs_modulus_Pa"] = r.voigt.youngs_modulus;
  j["voigt_poisson_ratio"] = r.voigt.poisson_ratio;
  j["local_valid"] = r.gauges.valid;
  j["local_fit_frames"] = r.gauges.fit_frames;
  j["local_stiffness_N_per_m"] = r.gauges.stiffness;
  j["local_youngs_modulus_Pa"] = r.gauges.youngs_modulus;
  j["curvature_youngs_modulus_Pa"] = r.gauges.curvature_modulus;
  j["predicted_local_stiffness_N_per_m"] = r.predicted_local_stiffness;
  j["shear_to_bending_deflection"] = r.shear_correction;
  j["loading_speed_m_per_s"] = r.quasi_static.loading_speed;
  j["max_kinetic_to_elastic"] = r.quasi_static.max_kinetic_to_elastic;
  return j;
}

}  // namespace shard::bending
