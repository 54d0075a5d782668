#include "shard/driver/stop_rules.hpp"

#include <fmt/format.h>

#include <csignal>

namespace shard::driver {
namespace {

// The signal that asked for a stop (0: none). A signal handler can only touch a lock-free flag,
// so this one flag is global.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int signal) { g_interrupted = signal; }

const char* signal_name(int signal) { return signal == SIGTERM ? "SIGTERM" : "SIGINT"; }

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

namespace {

// Whether every particle is slower than `speed` (m/s); stops at the first that is not. A run
// decomposed over MPI ranks answers over all ranks (RunState::Whole::all_slower_than: each rank
// looks at its own particles, the answers combined with a logical and), the same on every rank.
bool all_slower_than(const RunState& run, double speed) {
  if (run.whole && run.whole->all_slower_than) return run.whole->all_slower_than(speed);
  const Particles& p = run.sim.particles();
  const double limit2 = speed * speed;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.velocity[k].squaredNorm() >= limit2) return false;
  return true;
}

}  // namespace

void RestStop::on_start(RunState& run) {
  still_since_ = -1;
  look(run);
}

void RestStop::on_step(RunState& run) { look(run); }

void RestStop::look(RunState& run) {
  const double speed = run.scene.stop.rest_speed;
  if (!(speed > 0)) return;
  if (!all_slower_than(run, speed)) {
    still_since_ = -1;
    return;
  }
  const double now = run.sim.time();
  if (still_since_ < 0) still_since_ = now;
  // Half a step of slack: the times are sums of dt, and rest_time is rarely a whole number of them.
  if (now - still_since_ >= run.scene.stop.rest_time - 0.5 * run.sim.dt())
    run.request_stop(StopReason::Rest,
                     fmt::format("at rest: every particle slower than {} m/s since t = {:.6g} s ({} s)", speed,
                                 still_since_, run.scene.stop.rest_time));
}

InterruptStop::InterruptStop(std::int64_t at_step)
    : at_step_(at_step), previous_int_(std::signal(SIGINT, on_interrupt)), previous_term_(std::signal(SIGTERM, on_interrupt)) {
  g_interrupted = 0;
}

InterruptStop::~InterruptStop() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

void InterruptStop::on_step(RunState& run) {
  const std::int64_t s = run.sim.step_count();
  if (s == at_step_) g_interrupted = SIGINT;
  if (!g_interrupted) return;
  run.result.interrupt_signal = g_interrupted;
  run.request_stop(StopReason::Interrupted,
                   fmt::format("interrupted ({}) at step {}: checkpoint written; continue with shard run --restart {}",
                               signal_name(g_interrupted), s, run.result.output.string()));
}

}  // namespace shard::driver
