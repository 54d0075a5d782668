#pragma once
// A four-point bending run (run.h5) analysed: the set-up read back from the stored scene, the
// load curve, the crack, the fragments, the network's stiffness and the quasi-static check.
//
// Set-up inference (each figure can be overridden):
//  * the loading pins are the scene's [stop] load_walls (two cylinders), the supports the other
//    two cylinder walls; the beam axis runs from the first pin to the second, with its component
//    along the load direction removed; pin distance and span are measured along it between the
//    cylinders' axes;
//  * width and height are the extent of the spheres of the first frame across the beam axis
//    (width) and along the load direction (height).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shard/bending/beam_theory.hpp"
#include "shard/bending/crack_location.hpp"
#include "shard/bending/curve_analysis.hpp"
#include "shard/bending/local_deflection.hpp"
#include "shard/bending/network_stiffness.hpp"
#include "shard/io/json.hpp"

namespace shard::bending {

struct BendingOptions {
  CurveOptions curve;
  std::optional<double> span, pin_distance, width, height;  // m, override the inferred set-up
  double crack_window = 0;          // m; 0: two mean particle diameters
  double major_fragment = 0.05;     // a fragment holding at least this mass fraction is "major"
  double gauge_section = 0;         // m, width of the local-deflection sections; 0: two mean diameters
  double gauge_core = 0;            // m, height band around mid-height the sections use; 0: half the height
  // The local instrumentation reads a frame as elastic while at most this fraction of the bonds
  // has broken (anywhere for the deflection under the pins, between the pins for the curvature).
  // 0: before the first break. A resolved beam loses isolated bonds long before it cracks (the
  // seed-resolution beam: 20 of 1.35e6 by 0.46 mm of pin travel); random loss of a fraction phi
  // of the bonds lowers a network's modulus by the order of phi.
  double local_damage_limit = 0;
};

struct FragmentSummary {
  std::size_t count = 0;          // all fragments (single particles included)
  std::size_t major = 0;          // fragments with >= major_fragment of the mass
  std::vector<double> major_mass_fractions;
  std::vector<double> sizes;      // m, every fragment's equivalent diameter (heaviest first)
  double frame_time = 0;          // s, the frame analysed (the last)
};

struct QuasiStaticCheck {
  // max over rows before the first break with F >= 20 % F_max of kinetic / (bond + contact) energy
  double max_kinetic_to_elastic = 0;
  double loading_speed = 0;       // m/s, of the pins
  double load_time = 0;           // s, from contact onset to F_max
};

struct BendingReport {
  std::filesystem::path run;
  BendingGeometry geometry;
  std::string geometry_source;    // how each figure was obtained
  Vec3 centre = Vec3::Zero(), axis = Vec3::UnitX(), down = -Vec3::UnitZ();
  std::size_t particles = 0, bonds = 0;
  double mean_diameter = 0;       // m
  double length = 0;              // m, extent of the spheres along the beam axis
  BeamBondParameters bond;
  bool breakage = true;           // [simulation] breakage and the bond's own flag
  analysis::LoadCurve curve;
  CurveAnalysis analysis;
  CrackLocation crack;
  std::size_t breaks_before_peak = 0;  // bonds broken up to the F_max row (damage before failure)
  FragmentSummary fragments;
  VoigtEstimate voigt;
  analysis::LoadCurve local_curve;  // every frame after the first: F against the beam's own deflection
  LocalInstrumentation gauges;    // the beam's own deflection and curvature over the elastic frames
  double predicted_local_stiffness = 0;  // N/m, beam theory (eq. 14 + Timoshenko) on the curvature E
  QuasiStaticCheck quasi_static;
  double shear_correction = 0;    // Timoshenko shear / bending deflection for E/G of the Voigt estimate's nu
};

// Throws std::runtime_error with the path and the missing item when the run is not a bending run.
BendingReport analyse_bending_run(const std::filesystem::path& run, const BendingOptions& options = {});

// Human-readable summary (several lines).
std::string format_report(const BendingReport& r);

// The same figures as a JSON document (shard/io/json.hpp), SI units named in each key
// ("force_max_N"); figures that could not be measured are null. Format version 1.
inline constexpr int kBendingReportFormat = 1;
io::Json report_json(const BendingReport& r);

}  // namespace shard::bending
