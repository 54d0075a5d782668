#pragma once
// What the contrast diagnosis and the contrast calibration share (docs/explanation/diagnosis.md
// "Contrasts"): the sets read and checked against each other, the
// base model calibrated on the reference, the model's contrasts simulated on common packing
// seeds, and each set's measured contrast with its covariance. The statistics are
// shard/measure/contrast.hpp; this file turns measurement folders and runs into their inputs.
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "shard/measure/comparison.hpp"
#include "shard/measure/contrast.hpp"
#include "shard/measure/effect_library.hpp"
#include "shard/measure/group_scatter.hpp"
#include "shard/measure/rate_sensitivity.hpp"
#include "shard/measure/simulator.hpp"

namespace shard::measure {

struct ContrastSets {
  std::vector<measure::MeasurementSet> sets;
  std::vector<std::string> names;      // folder names, unique
  std::optional<std::size_t> reference;  // index into sets; none: each set against the consensus of the others
};

// Reads the folders; throws (naming them) when a set has fewer than two specimens at a rate, when
// the sets' specimen geometry or test conditions differ, when `reference` is not among them, or
// when fewer than two sets are given.
ContrastSets read_contrast_sets(const std::vector<std::filesystem::path>& folders, const std::string& reference);
// What read_contrast_sets checks once the sets are read, and that a set shares at least one
// loading rate with the reference (otherwise its batch and its rate are one difference).
void check_contrast_sets(const ContrastSets& sets);

// One (set, loading rate) group: its specimens' components and the reference it is held against.
struct ContrastGroup {
  std::size_t set = 0;
  double rate = 0;          // m/s
  double reference_rate = 0;  // the rate of the reference group (the nearest the reference has)
  std::vector<std::vector<double>> components;  // one row per specimen
};

// The base parameters fitted to the reference: Gauss-Newton on the logarithms of stiffness,
// peak force and peak displacement (the form-free part of a curve), each in units of its
// standard uncertainty, relative steps of 5 %. With more than two parameters (a form parameter
// such as bond.poisson_ratio) the post-peak regime's mean standardised residual joins the
// targets: the scale targets alone do not see the curve after the peak.
struct BaseCalibration {
  std::vector<std::string> keys;
  std::vector<double> start, values;
  std::vector<double> uncertainty;           // standard uncertainty of each value ((J'J)^-1 of the last step)
  std::vector<measure::ParameterRange> range;  // what the plugins accept (ParamSpec)
  std::vector<bool> at_range_bound;          // the last step asked for a value outside the range
  bool form_targets = false;                 // the post-peak regime was a target
  std::vector<std::string> path;  // one line per iteration; a step that raised the misfit says so
  // The path line whose values are returned: the last step the fit kept. A step that raises the
  // misfit beyond the runs' noise is halved back towards it instead of being taken.
  std::size_t returned_line = 0;
  std::vector<std::string> at_bound;  // parameters whose step was clamped in the last iteration
  measure::Comparison form_error;     // the calibrated base against the reference
};

class ContrastStudy {
 public:
  // `own_scatter_p`: ContrastOptions::own_scatter_p (0: every set in the pooled scatter).
  ContrastStudy(const ContrastSets& sets, Simulator& simulator, ModelPlan base, double own_scatter_p = 0);

  // The pooled scatter as the contrasts' decisions read it (contrast.hpp: ScatterEstimate).
  ScatterEstimate noise() const {
    return {scatter_.dof, static_cast<double>(contrast_component_names().size())};
  }
  // The specimens' scatter: pooled, and the groups that carry their own (group_scatter.hpp).
  const GroupScatter& scatter() const { return scatter_; }
  const std::vector<ContrastGroup>& groups() const { return groups_; }
  const ContrastSets& sets() const { return sets_; }

  // The parameters' values and ranges are the simulator's (its scene and plugins).
  BaseCalibration calibrate_base(const std::vector<std::string>& keys, int iterations, std::ostream& log);
  const ModelPlan& base() const { return base_; }

  // The rates every model must run at (all groups' rates and their references').
  std::vector<double> rates() const;

  // The simulated curves of a model at each rate of rates(), per packing seed; one batch for all.
  struct Simulated {
    std::vector<std::vector<measure::Curve>> curves;                // [rate][seed]
    std::vector<std::vector<std::vector<double>>> components;       // [rate][seed]: contrast_components
  };
  // Throws, naming the rate and the curve, when a run's curve has no rise to a peak: a model the
  // contrasts cannot read is refused here, so a diagnosis leaves it out (simulate_each) instead of
  // stopping where its contrast is taken.
  std::vector<Simulated> simulate(const std::vector<ModelPlan>& models, std::ostream& log);

  // The measured contrast of `set` (its groups concatenated) minus what the base model predicts
  // from the test conditions alone (another rate), with the inverse of its covariance.
  struct Contrast {
    std::vector<std::string> names;
    std::vector<double> difference;
    std::vector<std::vector<double>> weight;
    std::vector<std::size_t> groups;  // indices into groups()
    // The loading rates of its groups and their references (a rate effect is told apart from a
    // rate-independent one only across two or more), at the scene's one specimen size.
    DataCoverage coverage;
  };
  Contrast contrast(std::size_t set, const Simulated& base) const;
  // The set's rate dependence of its strength (rate_sensitivity.hpp), when the contrast spans two
  // or more of the set's own rates; `exponent` is subcritical growth's n it is held against.
  std::optional<RateSensitivity> rate_sensitivity(const Contrast& c, const Simulated& base, double exponent) const;
  // The model's contrast of `set`'s groups: effect minus base on each seed, averaged.
  std::vector<double> model_contrast(const Contrast& c, const Simulated& with_effect, const Simulated& base) const;
  // Per packing seed, `moved`'s components minus `from`'s over the contrast's groups, concatenated
  // as model_contrast concatenates them.
  std::vector<std::vector<double>> seed_moves(const Contrast& c, const Simulated& moved, const Simulated& from) const;

  // The contrast as curves: measured (set mean - reference mean) and simulated (model at the
  // set's rate - base at the reference's rate) forces in units of the peak force, against
  // displacement in units of the peak displacement; `nrmse` is their RMS difference.
  // `floor` is the NRMSE the two would show if the model's contrast were the true one: the RMS
  // of the measured contrast's standard uncertainty and of the simulated contrast's scatter over
  // the packing seeds (u_simulated, paired seed by seed).
  // The rising branch (up to the earlier of the set's and the model's mean peak) is where an
  // effect's form shows: after the peak a brittle curve drops in a step whose position moves with
  // the effect's fitted size, and the pointwise difference there measures that position (judged
  // by the components), not the form. rising_nrmse is taken over it (its floor: naming_floor).
  struct CurveContrast {
    std::vector<double> xi, measured, u_measured, simulated, u_simulated;
    std::vector<char> rising;  // the point lies on the rising branch
    double nrmse = 0, floor = 0;
    double rising_nrmse = 0;
  };
  CurveContrast curve_contrast(const Contrast& c, const Simulated& model, const Simulated& base) const;

 private:
  std::size_t rate_index(double rate) const;
  // The contrast components of every curve of `run`; throws for a curve with no rise to a peak.
  void read_components(Simulated& run) const;
  // The model's scale: its base's mean peak at the reference's (or the most common) rate.
  measure::ContrastScale simulated_scale(const Simulated& base) const;
  // Components of every seed of `model` at `rate`.
  const std::vector<std::vector<double>>& components(const Simulated& model, double rate) const;

  const ContrastSets& sets_;
  Simulator& simulator_;
  ModelPlan base_;
  std::vector<ContrastGroup> groups_;
  measure::ContrastScale measured_scale_;
  StiffnessBand band_;     // the contrasts' elastic line, measured and simulated (stiffness_band)
  double scale_rate_ = 0;  // the rate whose curves set both scales
  GroupScatter scatter_;
};

}  // namespace shard::measure
