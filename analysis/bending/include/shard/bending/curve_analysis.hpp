#pragma once
// The load curve of a four-point bending test, F (total force on the pins, N) over w (pin
// displacement, m), reduced to the figures the seed compares (sec. IV, Fig. 4 and 6).
//
// Definitions (the same for simulated and measured curves, so calibration compares like with like):
//  * F_max: the largest force; its row is the peak.
//  * initial stiffness k: least-squares line F = k w + c through the rising part before the peak
//    with fit_low F_max <= F <= fit_high F_max (default 10-40 %): past the seating of the pins and
//    before any damage. The line's w-intercept w0 = -c / k is the contact onset (toe correction).
//  * w_s,max = w(F_max) - w0: the deflection at failure, counted from the contact onset.
//  * E (eq. 14) from k; E_secant (eq. 14) from F_max / w_s,max, the seed's own way (sec. V.2);
//  * sigma_b (eq. 15) at F_max.
//  * failed: the force fell below failure_drop F_max after the peak (a brittle failure).
#include <cstddef>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "shard/analysis/load_curve.hpp"
#include "shard/bending/beam_theory.hpp"

namespace shard::bending {

struct CurveOptions {
  double fit_low = 0.10;   // fraction of F_max where the stiffness fit starts
  double fit_high = 0.40;  // ... and ends
  double failure_drop = 0.5;  // the curve failed when F fell below this fraction of F_max after the peak
  // > 0: the fit window is fit_low..fit_high of this force (N) instead of the curve's F_max, so
  // that a run stopped before failure (calibration's stiffness runs) is fitted on the same force
  // range as the test it stands for.
  double reference_force = 0;
  // Pin travel over which the reported smoothed peak averages the force (a load cell's low pass).
  double peak_window = 25e-6;  // m
  double window_force(double force_max) const { return reference_force > 0 ? reference_force : force_max; }
};

struct LinearFit {
  double slope = 0, intercept = 0;
  double r_squared = 0;
  std::size_t points = 0;
};

// Ordinary least squares y = slope x + intercept. Throws std::invalid_argument for fewer than
// two points, mismatched lengths or all x equal.
LinearFit fit_line(std::span<const double> x, std::span<const double> y);

struct CurveAnalysis {
  std::size_t rows = 0;
  std::size_t peak_row = 0;
  double force_max = 0;             // F_max, N
  double displacement_at_peak = 0;  // w(F_max) as recorded, m
  double fit_low = 0, fit_high = 0;  // the fit window, fractions of F_max
  LinearFit fit;                    // F = k w + c over the fit window
  double stiffness = 0;             // k, N/m
  double onset = 0;                 // w0 = -c / k, m
  double deflection_at_peak = 0;    // w_s,max = w(F_max) - w0, m
  double youngs_modulus = 0;        // E from k by eq. 14, Pa
  double youngs_modulus_secant = 0; // E from F_max / w_s,max by eq. 14, Pa
  double flexural_strength = 0;     // sigma_b at F_max by eq. 15, Pa
  bool failed = false;              // the force dropped below failure_drop F_max after the peak
  double final_force = 0;           // N, the last row
  // The largest mean force over peak_window of travel: at the final snap the raw curve often
  // spikes for 2-3 rows (1-3 ms); this shows by how much (reported, not used by calibration).
  double force_max_smoothed = 0;    // N
  double peak_window = 0;           // m, the window used
};

// Throws std::invalid_argument naming the problem when the curve is empty, the columns differ
// in length, the force never rises above zero, or the fit window holds fewer than 3 points.
CurveAnalysis analyse_curve(std::span<const double> displacement, std::span<const double> force,
                            const BendingGeometry& geometry, const CurveOptions& options = {});

// Reads a CSV with a header naming its columns (shard/io/csv.hpp: Shard's files and lab exports
// with ';', decimal commas and a units row): the displacement column is the first whose name starts
// with "displacement", "w", "Standardweg" or "Extension", the force column the first starting with
// "force", "F", "Standardkraft" or "Load" (any case). Units: a units row under the header is
// applied; without one, m and N, or mm and kN for a name ending in "_mm" or "_kN". Lines starting
// with '#' are comments. Throws std::runtime_error naming file:line:column on bad input.
analysis::LoadCurve read_curve_csv(const std::string& path);
// The file's "#! key = value" lines (a measurement file's set-up: span_mm, pin_distance_mm,
// width_mm, height_mm, and displacement = local | pins, what the displacement column measured).
std::map<std::string, std::string> read_curve_metadata(const std::string& path);
void write_curve_csv(const std::string& path, const analysis::LoadCurve& curve);

}  // namespace shard::bending
