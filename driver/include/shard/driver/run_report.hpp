#pragma once
// What a finished run tells its user: the closing lines (where the run file is, why the run
// stopped, the peak load and the quasi-static figure) and the load curve as CSV beside the run
// file (<run>_curve.csv: time_s, displacement_m, force_N), written when the scene has load walls.
#include <functional>
#include <string>

#include "shard/driver/run_observer.hpp"

namespace shard::driver {

using LineSink = std::function<void(const std::string&)>;

class RunReport : public RunObserver {
 public:
  explicit RunReport(LineSink out) : out_(std::move(out)) {}
  void on_finish(RunState& run) override;

 private:
  LineSink out_;
};

// Throws OutputError when the disk refuses the CSV; `out` (may be empty) is told where it went.
class CurveCsvWriter : public RunObserver {
 public:
  explicit CurveCsvWriter(LineSink out = {}) : out_(std::move(out)) {}
  void on_finish(RunState& run) override;

 private:
  LineSink out_;
};

}  // namespace shard::driver
