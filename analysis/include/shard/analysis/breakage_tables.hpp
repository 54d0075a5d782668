#pragma once
// The plates and the breakage curve as column tables (CSV / HDF5), in SI units.
#include <string>
#include <vector>

#include "shard/analysis/breakage_curve.hpp"
#include "shard/analysis/column_table.hpp"
#include "shard/analysis/plate_outcome.hpp"

namespace shard::analysis {

// One row per plate: run, value, seed, body, impact (speed, angle), broken, fragments, largest
// fraction, x10/x50/x90, fines, mass. `value_name` names the value column (a sweep's key; empty:
// no value and seed columns).
ColumnTable plate_table(const std::vector<PlateOutcome>& plates, const std::string& value_name = "");

enum class GroupedBy { impact_speed, value };

// One row per group: speed bin edges (or the value), plates, broken, share and its interval,
// impact speeds, fragments, x10/x50/x90 and the x50 interval.
ColumnTable group_table(const std::vector<BreakageGroup>& groups, GroupedBy by, const CurveOptions& options,
                        const std::string& value_name = "value");

}  // namespace shard::analysis
