#pragma once
// A force-displacement curve of one four-point bending test, measured or simulated: the one load
// curve type (shard/analysis/load_curve.hpp). The measurement workflow reads every curve with its
// standard uncertainties, the length of the curve (zero for a simulated one).
#include "shard/analysis/load_curve.hpp"

namespace shard::measure {

using Curve = analysis::LoadCurve;

}  // namespace shard::measure
