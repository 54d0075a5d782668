#pragma once
// What `shard sweep` leaves in its folder: tables (CSV and sweep.h5), pictures and report.md.
#include <iosfwd>

#include "shard/analysis/breakage_curve.hpp"
#include "shard/app/sweep_command.hpp"
#include "sweep_plan.hpp"

namespace shard {

void write_sweep_outputs(const SweepOptions& options, const SweepPlan& plan, const SweepResult& result,
                         const analysis::CurveOptions& curve, std::ostream& log);

}  // namespace shard
