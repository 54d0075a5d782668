#pragma once
// The contrast calibration: one effect (or two at once) added to the model of one set and sized
// so that the model's contrast against the reference matches the measured one (NLopt COBYLA on
// the contrast's chi^2, one run per packing seed per evaluation, common random numbers). The
// contrast NRMSE before and after shows the fall.
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "shard/measure/contrast_diagnosis.hpp"

namespace shard::measure {

struct ContrastCalibrationOptions {
  std::vector<std::string> params;  // base parameters fitted to the reference first
  int base_iterations = 3;
  int max_evaluations = 12;  // of the local fit, per effect
  // One effect: before the local fit, 0.5, 1, 2, 4 and 8 trial sizes each way in one batch, and
  // the local fit starts from the best. A brittle model's contrast chi^2 is rough in the size
  // (which bond breaks first changes the peak), so a local optimiser started at the linear size
  // can settle in a pit next to it.
  bool scan = true;
  bool lab_grain_size = false;  // the model at the reference's [test] grain_size
  ContrastOptions decide;
};

struct ContrastCalibration {
  std::size_t target = 0;                // the set fitted
  std::vector<CandidateEffect> effects;  // with plausible sizes resolved on the base run
  std::string scaled_sizes;
  BaseCalibration calibration;
  std::vector<double> values;        // the fitted value of each effect
  bool at_bound = false;             // a size ended at the range searched
  int evaluations = 0;
  double chi_square_before = 0, chi_square_after = 0;
  ContrastStudy::CurveContrast before, after;
  std::vector<std::pair<double, double>> scan;  // (value, contrast chi^2) of the bracketing scan
};

ContrastCalibration calibrate_contrast(const ContrastSets& sets, std::size_t target, Simulator& simulator,
                                       const ModelPlan& base, const std::vector<CandidateEffect>& chosen,
                                       const ContrastCalibrationOptions& options, std::ostream& log);

}  // namespace shard::measure
