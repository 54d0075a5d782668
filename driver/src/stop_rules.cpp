#include "shard/driver/stop_rules.hpp"

#include <fmt/format.h>

#include <csignal>

namespace shard::driver {
namespace {

// Set by SIGINT; a signal handler can only touch a lock-free flag, so this one flag is global.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) { g_interrupted = 1; }

}  // namespace

void LoadDropStop::on_series(RunState& run, const Energies&) {
  const double fraction = run.scene.stop.after_peak_fraction;
  if (fraction > 0 && run.bonds_broken() > 0 && run.sensor.load(run.sim) < fraction * run.result.peak_load)
    run.request_stop(StopReason::LoadDrop,
                     fmt::format("load fell below {:.0f} % of its peak after breakage", 100 * fraction));
}

void MaxDisplacementStop::on_series(RunState& run, const Energies&) {
  const double limit = run.scene.stop.max_displacement;
  if (limit > 0 && run.sensor.displacement(run.sim) >= limit)
    run.request_stop(StopReason::MaxDisplacement, "the loading walls reached max_displacement");
}

InterruptStop::InterruptStop(std::int64_t at_step) : at_step_(at_step), previous_(std::signal(SIGINT, on_interrupt)) {
  g_interrupted = 0;
}

InterruptStop::~InterruptStop() { std::signal(SIGINT, previous_); }

void InterruptStop::on_step(RunState& run) {
  const std::int64_t s = run.sim.step_count();
  if (s == at_step_) g_interrupted = 1;
  if (g_interrupted)
    run.request_stop(StopReason::Interrupted,
                     fmt::format("interrupted (SIGINT) at step {}: checkpoint written; continue with shard run "
                                 "--restart {}",
                                 s, run.result.output.string()));
}

}  // namespace shard::driver
