#pragma once
// The progress line: step, time, kinetic energy, load, bonds and the estimated time left. On a
// terminal (std::cerr on a tty) it rewrites itself every second; in a log file a line appears
// every 10 s. The line is closed with a newline when the run ends.
#include <chrono>
#include <iosfwd>

#include "shard/driver/run_observer.hpp"

namespace shard::driver {

class ProgressPrinter : public RunObserver {
 public:
  explicit ProgressPrinter(std::ostream& out);
  void on_start(RunState& run) override;
  void on_series(RunState& run, const Energies& energies) override;
  void on_finish(RunState& run) override;

 private:
  std::ostream& out_;
  bool tty_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace shard::driver
