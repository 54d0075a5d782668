#pragma once
// The beam's own deflection, as a laboratory's local instrumentation measures it (the seed,
// sec. V.2: "measured by means of local instrumentation"), and the network's own modulus from
// the curvature between the pins, both over the frames of the elastic part of a run.
//
// Pin travel (the crosshead) counts the Hertz indentation of pins and supports on top of the
// beam's deflection. The particles' displacements do not: a sphere is rigid, the indentation is
// in the wall contact. So the deflection under a pin relative to the supports is measured on the
// particles themselves:
//   w_local = mean u at the two pin stations - mean u at the two support stations,
// u the displacement along the load direction, read at a station from a least-squares line
// u(s) through the particles within half a `section_width` of s = +-d_S/2 (pins) or s = +-L/2
// (supports) and within half a `core_height` of mid-height (the neutral axis, away from the
// contact layers): a yoke-mounted LVDT.
// For an Euler-Bernoulli beam w_local is eq. 14's w_s; a Timoshenko beam adds the shear
// deflection F a / (2 k_s G A) of the outer spans.
#include <cstddef>
#include <span>
#include <vector>

#include "shard/bending/beam_theory.hpp"
#include "shard/bending/curve_analysis.hpp"
#include "shard/types.hpp"

namespace shard::bending {

struct SectionGauges {
  Vec3 centre = Vec3::Zero();  // beam centre (mid-height, between the pins)
  Vec3 axis = Vec3::UnitX();   // along the beam
  Vec3 down = -Vec3::UnitZ();  // the load direction
  double section_width = 0;    // m, along the beam (default in bending_run: 2 mean diameters)
  double core_height = 0;      // m, around mid-height (default in bending_run: half the height)
};

// Deflection under the pins relative to the supports between two frames of the same particles.
// Throws std::invalid_argument when a section holds no particle.
double local_deflection(std::span<const Vec3> reference, std::span<const Vec3> deformed, const SectionGauges& gauges,
                        const BendingGeometry& geometry);

// One row per analysed frame.
struct LocalFrame {
  double time = 0;
  double force = 0;       // N, total pin force at the frame (from the series)
  double deflection = 0;  // m, w_local
  double curvature = 0;   // 1/m, between the pins (curvature_modulus's fit)
};

struct LocalInstrumentation {
  std::vector<LocalFrame> frames;   // frames before the first break and the peak (BendingOptions::local_damage_limit)
  LinearFit deflection_fit;         // F = k_local w_local + c over the fit window
  double stiffness = 0;             // k_local, N/m
  double youngs_modulus = 0;        // eq. 14 on k_local (bending + shear deflection of the beam), Pa
  LinearFit moment_fit;             // M = EI kappa + c over the fit window
  double curvature_modulus = 0;     // EI / I: the network's own E in the constant-moment zone, Pa
  std::size_t fit_frames = 0;
  bool valid = false;               // at least 3 frames in the window, positive slopes
  std::size_t breaks_allowed = 0;   // "the first break" is the first after this many (BendingOptions)
};

// Fits over the frames with fit_low F_max <= F <= fit_high F_max (the curve's options).
LocalInstrumentation fit_local_instrumentation(std::vector<LocalFrame> frames, const BendingGeometry& geometry,
                                               double force_max, const CurveOptions& options);

// The beam-theory prediction of the local stiffness from the network's own moduli: eq. 14 with
// E, plus Timoshenko's shear deflection with G = E / (2 (1 + nu)).
double predicted_local_stiffness(const BendingGeometry& geometry, double youngs_modulus, double poisson_ratio);

}  // namespace shard::bending
