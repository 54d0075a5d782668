#include "shard/driver/progress_printer.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace shard::driver {
namespace {

std::string seconds_text(double s) {
  if (!std::isfinite(s)) return "--";
  if (s < 120) return fmt::format("{:.0f}s", s);
  if (s < 7200) return fmt::format("{:.0f}m{:02.0f}s", std::floor(s / 60), std::fmod(s, 60));
  return fmt::format("{:.1f}h", s / 3600);
}

}  // namespace

ProgressPrinter::ProgressPrinter(std::ostream& out) : out_(out), tty_(&out == &std::cerr && isatty(STDERR_FILENO)) {}

void ProgressPrinter::on_start(RunState&) { last_ = std::chrono::steady_clock::now(); }

void ProgressPrinter::on_series(RunState& run, const Energies& e) {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ <= std::chrono::seconds(tty_ ? 1 : 10)) return;
  last_ = now;
  const Simulation& sim = run.sim;
  const std::int64_t s = sim.step_count();
  const double elapsed = std::chrono::duration<double>(now - run.wall_start).count();
  const double rate = static_cast<double>(s - run.start_step) / std::max(1e-9, elapsed);
  fmt::print(out_, "step {:>9} t={:.4e}s KE={:.3e}J load={:.4g}N bonds {}/{} broken {} {:.0f} steps/s ETA {}{}", s,
             sim.time(), e.kinetic, run.sensor.load(sim), run.bonds_intact(), run.result.bonds_initial,
             run.bonds_broken(), rate, seconds_text(static_cast<double>(run.total_steps - s) / rate),
             tty_ ? "\r" : "\n");
  out_.flush();
}

void ProgressPrinter::on_finish(RunState&) { fmt::print(out_, "\n"); }

}  // namespace shard::driver
