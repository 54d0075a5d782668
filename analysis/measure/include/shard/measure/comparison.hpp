#pragma once
// Measured against simulated four-point bending curves (`shard compare`).
//
// Common grid. Every curve is sampled at the same loading-pin displacements w = xi w_ref, with
// w_ref the mean measured displacement at peak, xi in [0, xi_end] (xi_end: the shortest measured
// curve, at most CompareOptions::max_xi). A simulated curve that stopped earlier (the run ends
// once the load has dropped after breakage) is continued with its last force.
//
// Bands. Measured: mean over the specimens, standard uncertainty of that mean
//   u_m^2 = s^2 / n + (u_F^2 + (dF/dw u_w)^2) / n      (specimen scatter + sensor noise)
// Simulated: mean over the packing-seed replicates, u_s^2 = s^2 / n. The standardised residual is
//   r = (F_sim - F_meas) / sqrt(u_m^2 + u_s^2).
//
// Regimes, on the measured mean curve: toe (F < 10 % F_max on the rise), elastic (10-60 %),
// pre-peak (60-90 %), peak (the points around the maximum with F >= 90 % F_max), post-peak.
// Neighbouring residuals share the specimen scatter, so a regime's mean residual is treated as
// one score: a regime fails "beyond noise" when |score| > noise_threshold (2).
//
// Reference distribution of a score (CompareOptions::score_reference). The variances in it are
// estimated from a few specimens and replicates, so a score is Student-t distributed, with the
// Welch-Satterthwaite degrees of freedom of its variance (RegimeResult::dof, FeatureComparison::dof:
// the specimen and replicate scatter estimated with n - 1, the sensor noise known). `Normal` reads
// the raw ratio as N(0, 1); `Welch` converts it to the normal score of equal tail probability, so
// that every later sum of squares is a chi-square in fact, not only in name.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "shard/measure/features.hpp"
#include "shard/measure/measurements.hpp"

namespace shard::measure {

enum class Regime : std::size_t { Toe, Elastic, PrePeak, Peak, PostPeak };
inline constexpr std::size_t kRegimeCount = 5;
std::string_view regime_name(Regime r);

enum class ScoreReference { Normal, Welch };
// "normal" / "welch"; throws std::invalid_argument naming the accepted names.
ScoreReference parse_score_reference(std::string_view name);

struct CompareOptions {
  std::size_t grid_points = 120;
  double max_xi = 3;             // post-peak beyond 3 w_ref carries no information on the model
  double noise_threshold = 2;    // |score| beyond which a difference is not noise
  // Crack position, fragment x50 and count are always reported; they enter the verdict and the
  // residual vector that diagnose explains only when judged. On a few-hundred-sphere beam the
  // crack sits at one of two sites by the packing's chance, and three replicates do not estimate
  // that scatter: judged, they made correct effect models fail the remainder test. The crack
  // initiation force and the failure displacement are judged with them (features.hpp:
  // judged_by_default, fracture_feature).
  bool judge_fracture = false;
  ScoreReference score_reference = ScoreReference::Normal;
};

struct Band {
  std::vector<double> mean, u;
  // The part of u^2 estimated from the curves' scatter (s^2 / n; measured side only: the simulated
  // u^2 is all scatter), and the degrees of freedom of that estimate (n - 1); the rest of the
  // measured u^2 is sensor noise, known.
  std::vector<double> sampled_variance;
  double sampled_dof = 0;
};

struct RegimeResult {
  Regime regime = Regime::Toe;
  std::size_t first = 0, last = 0;  // grid indices [first, last)
  double mean_residual = 0;         // mean standardised residual (as a normal score under Welch)
  double dof = 0;                   // Welch-Satterthwaite degrees of freedom of its variance
  double rms_residual = 0;
  double chi_square = 0;            // sum r^2 (points treated as independent: an upper bound)
  double relative_error = 0;        // (sum F_sim - sum F_meas) / sum F_meas
  bool beyond_noise = false;
  std::size_t points() const { return last - first; }
};

struct FeatureComparison {
  Feature feature = Feature::Stiffness;
  std::size_t measured_count = 0, simulated_count = 0;
  double measured = 0, u_measured = 0, simulated = 0, u_simulated = 0;
  double error = 0, relative_error = 0;
  double u_measured_sampled = 0;  // the specimen-scatter part of u_measured (the rest is sensor noise)
  double score = 0;  // error / combined uncertainty (as a normal score under Welch); NaN when it is zero
  double dof = 0;    // Welch-Satterthwaite degrees of freedom of the combined variance
  bool beyond_noise = false;
  bool judged = true;  // part of the verdict and the residual vector (CompareOptions::judge_fracture)
};

// Named standardised residual components (regime means, then feature scores): what
// `shard diagnose` explains.
struct ResidualVector {
  std::vector<std::string> names;
  std::vector<double> values;
};

struct Comparison {
  double reference_displacement = 0;  // w_ref, m
  double measured_peak_force = 0;     // of the mean curve, N
  std::vector<double> xi;
  std::vector<std::vector<double>> measured_curves, simulated_curves;  // force on the grid, per curve
  Band measured, simulated;
  std::vector<double> residual;  // standardised, per grid point
  std::array<RegimeResult, kRegimeCount> regimes{};
  std::vector<FeatureComparison> features;
  double nrmse = 0;  // RMS(F_sim - F_meas) / F_max,meas on the grid
  std::string verdict;
  bool adequate = false;
  CompareOptions options;  // what it was scored with (with_simulated_band rescores alike)

  ResidualVector residual_vector() const;
  // The NRMSE that noise alone gives: RMS over the grid of the combined band sqrt(u_m^2 + u_s^2),
  // over F_max,meas (the expected NRMSE of a model that is the truth). NRMSEs below it differ by
  // noise.
  double noise_nrmse() const;
};

// Feature values of an observation (a measured specimen or a simulated replicate).
FeatureValues observation_features(const Specimen& s, const Metadata& metadata);

// Force of a curve at displacement w: linear interpolation on its rising-displacement envelope,
// its last force beyond the end.
double force_at(const Curve& c, double w);

Comparison compare(const std::vector<Specimen>& measured, const Metadata& metadata,
                   const std::vector<Specimen>& simulated, const CompareOptions& options = {});

// `c` rescored with the simulated band (per grid point and per feature) of `reference`, a
// comparison of another model with the same measurements: residuals, regimes, feature scores and
// verdict; NRMSE and means unchanged. Candidates judged on one frozen band cannot lower their
// chi^2 by scattering more (a wider band shrinks every standardised residual): diagnose scores
// every model against the base model's band. Throws when the grids differ.
Comparison with_simulated_band(const Comparison& c, const Comparison& reference);

// The Gaussian likelihood's variance term of `c` against `reference` over the residual vector's
// components: sum of ln(v_c / v_ref), v the combined variance u_m^2 + u_s^2 (a regime's: its
// points' mean; a feature's: its own). -2 ln L = chi^2 + sum ln v + const, so chi^2 plus this
// term compares models on their likelihood: a model whose replicates scatter more pays for its
// wider band (zero for the reference itself). Components missing on either side are skipped.
double log_variance_ratio(const Comparison& c, const Comparison& reference);

}  // namespace shard::measure
